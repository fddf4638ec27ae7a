"""What the command line and serve refuse, the module refuses alike, before any work: sizes, options,
lights, exposures; and what it hands out cannot be changed by mistake."""
import math
import pathlib

import numpy as np
import pytest

import phongcl
from opencl_required import needs_device

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"
DEFAULT = SCENES / "default" / "scene.json"
DEFAULT_GBUFFER = SCENES / "default" / "gbuffer.exr"


def small_gbuffer(height=4, width=6):
    P = np.zeros((height, width, 3), np.float32)
    N = np.zeros((height, width, 3), np.float32)
    N[..., 2] = 1
    return phongcl.GBuffer(P, N, np.zeros((height, width), np.float32))


def test_oversized_arrays_are_refused_before_any_conversion():
    # Broadcast float64 arrays: converting them would allocate 3 GB first; the size check comes before.
    huge = np.broadcast_to(np.float64(0), (16385, 16384, 3))
    with pytest.raises(ValueError, match=r"16384 x 16385 = 268451840 pixels: more than max_pixels=268435456"):
        phongcl.GBuffer(huge, huge, np.broadcast_to(np.float64(0), (16385, 16384)))
    enormous = np.broadcast_to(np.float32(0), (100000, 100000, 3))
    with pytest.raises(ValueError, match="100000 x 100000 = 10000000000 pixels"):
        phongcl.GBuffer(enormous, enormous, np.broadcast_to(np.float32(0), (100000, 100000)))
    with pytest.raises(ValueError, match="max_pixels=23"):
        phongcl.GBuffer(np.zeros((4, 6, 3)), np.zeros((4, 6, 3)), np.zeros((4, 6)), max_pixels=23)
    assert phongcl.GBuffer(np.zeros((4, 6, 3)), np.zeros((4, 6, 3)), np.zeros((4, 6)), max_pixels=24).width == 6


def test_positions_and_normals_are_read_only():
    gb = small_gbuffer()
    for name in ("P", "N", "material"):
        array = getattr(gb, name)
        with pytest.raises(ValueError, match="read-only"):
            array[...] = 1


@pytest.mark.parametrize("exposure", [math.nan, math.inf, 1e308, -1000])
def test_png_exposure_is_checked_first(tmp_path, exposure):
    with pytest.raises(ValueError, match=r"exposure must be a finite number of stops in \[-40, 40\]"):
        phongcl.write_png(str(tmp_path / "x.png"), np.zeros((2, 2, 4), np.float32), exposure=exposure)
    assert not (tmp_path / "x.png").exists()


@needs_device
def test_options_are_checked_as_the_command_line_checks_them():
    scene, gb = phongcl.load_scene(str(DEFAULT)), phongcl.read_gbuffer(str(DEFAULT_GBUFFER))
    with pytest.raises(ValueError, match=r"lanes must be 0 \(the device's choice\), 1, 2, 4, 8 or 16 \(got -1\)"):
        phongcl.Relighter(scene, gb, lanes=-1)
    with pytest.raises(TypeError, match="device must be None, an index .int. or a name .str., not float 1.5"):
        phongcl.Relighter(scene, gb, device=1.5)


@needs_device
def test_lights_are_checked_against_the_scene_and_take_numpy_arrays():
    scene, gb = phongcl.load_scene(str(DEFAULT)), phongcl.read_gbuffer(str(DEFAULT_GBUFFER))
    relighter = phongcl.Relighter(scene, gb)
    count = len(scene.materials)
    with pytest.raises(ValueError, match=f"material index 99 is out of range .the scene has {count} materials"):
        relighter.set_lights([{"type": "point", "position": [0, 1, 0], "materials": [99]}])
    with pytest.raises(ValueError, match="must be a finite"):
        relighter.set_lights([{"type": "point", "position": [math.nan, 1, 0]}])
    relighter.set_lights([{"type": "point", "position": np.array([1.0, 2.0, 3.0]), "color": np.float32(0.5) * np.ones(3)},
                          {"type": "directional", "direction": (np.float64(0), -1, 0)}])
    assert relighter.shade().shape == (gb.height, gb.width, 4)
