"""The Python module against an independent NumPy reference, relit in a loop, and on bad inputs."""
import json
import math
import os
import pathlib

import numpy as np
import pytest

import phongcl
import numpy_reference
from accuracy_bound import RELATIVE_BOUND
from opencl_required import needs_device

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"
DEFAULT = SCENES / "default" / "scene.json"
DEFAULT_GBUFFER = SCENES / "default" / "gbuffer.exr"


@pytest.fixture(scope="module")
def scene():
    return phongcl.load_scene(str(DEFAULT))


@pytest.fixture(scope="module")
def gbuffer():
    return phongcl.read_gbuffer(str(DEFAULT_GBUFFER))


def check_against_reference(image, scene, gb, step):
    expected = numpy_reference.shade(scene, gb.P, gb.N, gb.material)
    shaded = expected[..., 3] == 1
    assert shaded.sum() > 1000, "the test scene should have shaded pixels"
    np.testing.assert_array_equal(image[~shaded], expected[~shaded].astype(np.float32), err_msg=step + ": background")
    error, worst = numpy_reference.worst_relative_error(image, expected, shaded)
    assert error <= RELATIVE_BOUND, (
        f"{step}: max relative error {error:.3g} at pixel (x={worst[1]}, y={worst[0]}) channel {'RGB'[worst[2]]}: "
        f"kernel {image[worst]:.9g}, reference {expected[worst]:.9g}")


@needs_device
def test_kernel_matches_the_numpy_double_reference(scene, gbuffer):
    relighter = phongcl.Relighter(scene, gbuffer, device=None, precision="precise")
    image = relighter.shade()
    assert image.shape == (gbuffer.height, gbuffer.width, 4) and image.dtype == np.float32
    check_against_reference(image, scene, gbuffer, "default scene")


@needs_device
def test_a_moving_light_relit_in_a_loop(scene, gbuffer):
    relighter = phongcl.Relighter(scene, gbuffer)
    relighter.shade()
    previous = None
    for step in range(6):
        angle = 2 * math.pi * step / 6
        lights = [{"type": "point", "position": [6 * math.cos(angle), 5, 6 * math.sin(angle)], "color": [1, 0.9, 0.8]},
                  {"type": "directional", "direction": [-0.3, -1, -0.5], "color": [0.2, 0.2, 0.2]}]
        relighter.set_lights(lights)
        image = relighter.shade()
        timings = relighter.last_timings
        if step > 0:
            # Same light count and types: the same kernel, and the G-buffer stays on the device.
            assert not timings["rebuilt"] and not timings["gbuffer_uploaded"], f"step {step}: {timings}"
            assert np.abs(image - previous).max() > 1e-3, f"step {step}: the light moved but the image did not change"
        check_against_reference(image, relighter.scene, gbuffer, f"step {step}")
        previous = image


@needs_device
def test_shade_writes_into_a_callers_array(scene, gbuffer):
    relighter = phongcl.Relighter(scene, gbuffer)
    out = np.zeros((gbuffer.height, gbuffer.width, 4), dtype=np.float32)
    returned = relighter.shade(out=out)
    assert returned is out or np.shares_memory(returned, out)
    np.testing.assert_array_equal(out, relighter.shade())
    with pytest.raises(ValueError, match="C-contiguous float32"):
        relighter.shade(out=np.zeros((gbuffer.height, gbuffer.width, 4), dtype=np.float64))
    with pytest.raises(ValueError, match="C-contiguous float32"):
        relighter.shade(out=np.zeros((gbuffer.height, gbuffer.width, 4), dtype=np.float32)[:, ::-1])
    with pytest.raises(ValueError, match=r"out must have shape \(%d, %d, 4\), got \(%d, %d, 3\)" % (
            gbuffer.height, gbuffer.width, gbuffer.height, gbuffer.width)):
        relighter.shade(out=np.zeros((gbuffer.height, gbuffer.width, 3), dtype=np.float32))


@needs_device
def test_the_report_counts_pixels_and_gives_the_recipe(scene, gbuffer):
    relighter = phongcl.Relighter(scene, gbuffer)
    image = relighter.shade()
    report = relighter.last_report
    shaded = int((image[..., 3] == 1).sum())
    assert report["counts"]["shaded"] == shaded
    assert report["counts"]["shaded"] + report["counts"]["background"] == gbuffer.width * gbuffer.height
    assert report["tiles"] == 1
    assert report["kernel_summary"] == relighter.kernel_summary
    assert any(reason.startswith("precision") for reason in report["recipe_reasons"])


@needs_device
def test_arrays_of_other_dtypes_and_layouts_are_converted(scene, gbuffer):
    P, N, material = gbuffer.P, gbuffer.N, np.array(gbuffer.material)
    expected = phongcl.Relighter(scene, phongcl.GBuffer(P=P, N=N, material=material)).shade()
    # float64, a Fortran-ordered copy, a transposed view and integer indices give the same G-buffer.
    converted = phongcl.GBuffer(P=P.astype(np.float64), N=np.asfortranarray(N),
                                material=np.where(material < 0, -1, material).astype(np.int32))
    np.testing.assert_array_equal(phongcl.Relighter(scene, converted).shade(), expected)
    transposed = np.ascontiguousarray(P.transpose(1, 0, 2)).transpose(1, 0, 2)
    assert not transposed.flags["C_CONTIGUOUS"]
    np.testing.assert_array_equal(
        phongcl.Relighter(scene, phongcl.GBuffer(P=transposed, N=N, material=material)).shade(), expected)


def test_the_material_plane_is_a_read_only_view(gbuffer):
    view = gbuffer.material
    assert view.shape == (gbuffer.height, gbuffer.width) and view.dtype == np.float32
    assert not view.flags["WRITEABLE"] and not view.flags["OWNDATA"]


def test_wrong_shapes_are_clear_errors(gbuffer):
    P, N, material = gbuffer.P, gbuffer.N, gbuffer.material
    with pytest.raises(ValueError, match=r"N must have shape \(480, 640, 3\), got \(480, 640\)"):
        phongcl.GBuffer(P=P, N=N[..., 0], material=material)
    with pytest.raises(ValueError, match=r"material must have shape \(480, 640\)"):
        phongcl.GBuffer(P=P, N=N, material=material[:10])
    with pytest.raises(ValueError, match=r"P must have shape \(H, W, 3\)"):
        phongcl.GBuffer(P=P[0], N=N, material=material)
    with pytest.raises(ValueError):
        phongcl.write_exr("never-written.exr", np.zeros((4, 4, 2), dtype=np.float32))
    assert not os.path.exists("never-written.exr")


def test_bad_files_and_values_raise_the_command_lines_messages(tmp_path, scene):
    with pytest.raises(phongcl.InputError, match="no-such.exr: no such file"):
        phongcl.read_gbuffer(str(tmp_path / "no-such.exr"))
    with pytest.raises(phongcl.InputError, match="unknown key 'colour' in the top level"):
        phongcl.Scene.from_dict({"lights": [], "colour": 1})
    with pytest.raises(phongcl.InputError, match=r"unknown light type 'mesh' in lights\[0\]"):
        phongcl.Scene.from_dict({"camera": {"eye": [0, 0, 5]}, "lights": [{"type": "mesh"}]})
    with pytest.raises(phongcl.InputError, match=r"missing key 'shape' in lights\[0\]"):
        phongcl.Scene.from_dict({"camera": {"eye": [0, 0, 5]}, "lights": [{"type": "area"}]})


@needs_device
def test_the_environment_is_set_in_the_scene_files_form_and_removed_by_none(gbuffer):
    document = json.loads(DEFAULT.read_text())
    world = {"type": "environment", "color": [0.2, 0.3, 0.4], "strength": 2, "shadows": False}
    relighter = phongcl.Relighter(phongcl.Scene.from_dict(document), gbuffer)
    without = relighter.shade()
    relighter.set_environment(world)
    lit = relighter.shade()
    document["lights"].append(world)
    np.testing.assert_array_equal(lit, phongcl.Relighter(phongcl.Scene.from_dict(document), gbuffer).shade())
    assert (lit[..., :3] - without[..., :3]).max() > 1e-2, "the world added no light"
    relighter.set_environment(None)
    np.testing.assert_array_equal(relighter.shade(), without)
    with pytest.raises(phongcl.InputError, match=r"environment.*not both or neither"):
        relighter.set_environment({"type": "environment"})


@needs_device
def test_area_lights_are_set_in_the_scene_files_form(gbuffer):
    document = json.loads(DEFAULT.read_text())
    area = {"type": "area", "shape": "rect", "position": [0, 4, 2], "direction": [0, -1, -0.3], "size": [2, 1],
            "color": [2, 2, 2]}
    relighter = phongcl.Relighter(phongcl.Scene.from_dict(document), gbuffer)
    without = relighter.shade()
    relighter.set_area_lights([area])
    lit = relighter.shade()
    assert not relighter.last_timings["gbuffer_uploaded"], "an area light is an update, not a new frame"
    document["lights"].append(area)
    expected = phongcl.Relighter(phongcl.Scene.from_dict(document), gbuffer).shade()
    np.testing.assert_array_equal(lit, expected)  # the same kernel on the same inputs
    assert (lit[..., :3] - without[..., :3]).max() > 1e-2, "the area light added no light"
    with pytest.raises(phongcl.InputError, match=r"area_lights\[0\].*set_lights takes those"):
        relighter.set_area_lights([{"type": "point", "position": [0, 1, 0], "color": [1, 1, 1]}])
    with pytest.raises(phongcl.InputError, match=r"area_lights\[0\]"):
        relighter.set_area_lights([dict(area, size=[0, 1])])
    with pytest.raises(phongcl.InputError, match=r"set_area_lights takes those"):
        relighter.set_lights([area])
    # The scene's area lights come back as AreaLight objects, and go in as them too.
    held = relighter.scene.area_lights
    assert [(a.shape, a.size, a.color) for a in held] == [("rect", [2.0, 1.0], [2.0, 2.0, 2.0])]
    held[0].shape = "disk"
    relighter.set_area_lights(held)
    document["lights"][-1] = dict(area, shape="disk", size=2)
    np.testing.assert_array_equal(relighter.shade(), phongcl.Relighter(phongcl.Scene.from_dict(document), gbuffer).shade())
    held[0].size = [-1, -1]
    with pytest.raises(ValueError, match=r"area_lights\[0\]\.size: must be finite and > 0"):
        relighter.set_area_lights(held)
    held[0].size = [1e20, 1e20]  # its area and axes, squared in float, overflowed to NaN pixels
    with pytest.raises(ValueError, match=r"area_lights\[0\]\.size: must be at most 1e\+18"):
        relighter.set_area_lights(held)
    with pytest.raises(phongcl.InputError, match=r"size\[0\] must be at most 1e\+18 \(got 1e\+20\)"):
        relighter.set_area_lights([dict(area, size=[1e20, 1])])
    with pytest.raises(ValueError, match="'ellipse' is not an area light shape"):
        held[0].shape = "ellipse"


@needs_device
def test_bad_changes_are_refused(scene, gbuffer):
    relighter = phongcl.Relighter(scene, gbuffer)
    with pytest.raises(phongcl.InputError, match=r"lights\[0\]\.color\[0\] must be >= 0"):
        relighter.set_lights([{"type": "point", "position": [0, 1, 0], "color": [-1, 0, 0]}])
    with pytest.raises(ValueError, match=r"lights\[0\]\.position: must be finite"):
        relighter.set_lights([phongcl.Light("point", position=[math.nan, 0, 0])])
    with pytest.raises(phongcl.InputError, match="material"):
        relighter.set_materials(scene.materials[:1])  # the G-buffer uses indices up to 4
    with pytest.raises(RuntimeError, match="no OpenCL device matches"):
        phongcl.Relighter(scene, gbuffer, device="no-such-device-anywhere")
    with pytest.raises(ValueError, match="precision"):
        phongcl.Relighter(scene, gbuffer, precision="sloppy")
    check_against_reference(relighter.shade(), scene, gbuffer, "after refused changes")


def test_scene_from_dict_reads_the_files_form():
    scene = phongcl.Scene.from_dict({
        "camera": {"eye": [0, 1, 6]}, "ambient": [0.1, 0.1, 0.1],
        "lights": [{"type": "directional", "direction": [-1, -1, -1], "color": [0.5, 0.5, 0.5]}],
        "materials": [{"name": "red", "ka": [0.2, 0, 0], "kd": [0.8, 0.1, 0.1], "ks": [0.5, 0.5, 0.5], "shininess": 32}],
    })
    assert scene.camera.eye == [0, 1, 6]
    assert scene.lights[0].type == "directional" and scene.lights[0].color == [0.5, 0.5, 0.5]
    assert scene.materials[0].name == "red" and scene.materials[0].shininess == 32


def test_a_material_names_its_specular_model():
    material = phongcl.Material()
    assert material.specular_model == "phong"
    material.specular_model = "blinn-phong-normalized"
    assert material.specular_model == "blinn-phong-normalized"
    with pytest.raises(ValueError, match="not a specular model"):
        material.specular_model = "blinn"
    scene = phongcl.Scene.from_dict({"materials": [{"ks": [1, 1, 1], "specular_model": "phong-normalized"}]})
    assert scene.materials[0].specular_model == "phong-normalized"


def test_a_principled_materials_inputs_are_settable():
    scene = phongcl.Scene.from_dict({"materials": [{"specular_model": "principled", "base_color": [0.8, 0.2, 0.1],
                                                    "metallic": 1, "roughness": 0.3}]})
    material = scene.materials[0]
    assert material.specular_model == "principled" and material.metallic == 1 and material.roughness == 0.3
    material.roughness, material.specular, material.specular_tint = 0.6, 1.0, 0.5
    material.base_color = (0.1, 0.2, 0.3)
    assert (material.roughness, material.specular, material.specular_tint) == (0.6, 1.0, 0.5)
    assert tuple(material.base_color) == pytest.approx((0.1, 0.2, 0.3))


def test_a_principled_version_2_materials_inputs_are_settable():
    scene = phongcl.Scene.from_dict({"materials": [{"specular_model": "principled", "version": 2, "ior": 1.45,
                                                    "specular_tint": [1, 0.5, 0.25], "diffuse_roughness": 0.5}]})
    material = scene.materials[0]
    assert (material.version, material.ior, material.specular_ior_level) == (2, 1.45, 0.5)
    assert tuple(material.specular_tint_color) == pytest.approx((1, 0.5, 0.25))
    assert material.diffuse_roughness == 0.5
    material.ior, material.specular_ior_level, material.diffuse_roughness = 3.0, 0.25, 1.0
    assert (material.ior, material.specular_ior_level, material.diffuse_roughness) == (3.0, 0.25, 1.0)


@needs_device
def test_shadows_are_a_relighter_option(scene, gbuffer):
    casting = phongcl.load_scene(str(DEFAULT))
    lights = casting.lights
    for light in lights:
        light.shadows = True
    casting.lights = lights
    shadowed = phongcl.Relighter(casting, gbuffer, shadows="geometry")
    image = shadowed.shade()
    assert shadowed.last_report["shadows"].startswith("geometry: ")
    unshadowed = phongcl.Relighter(casting, gbuffer, shadows="off")
    plain = unshadowed.shade()
    assert unshadowed.last_report["shadows"] == ""
    check_against_reference(plain, scene, gbuffer, "shadows off")
    assert (image[..., :3] < plain[..., :3]).any(axis=2).sum() > 100, "the default scene's objects shadow each other"
    assert (image[..., :3] <= plain[..., :3]).all()
    with pytest.raises(ValueError, match="shadow mode"):
        phongcl.Relighter(casting, gbuffer, shadows="sideways")
    with pytest.raises(ValueError, match="thickness"):
        phongcl.Relighter(casting, gbuffer, shadows="screen", shadow_thickness="-3")
    with pytest.raises(ValueError, match="shadow rays"):
        phongcl.Relighter(casting, gbuffer, shadow_rays=0)


@needs_device
def test_area_light_groups_come_back_apart(tmp_path, scene, gbuffer):
    document = json.loads(DEFAULT.read_text())
    document["lights"].append({"type": "area", "shape": "disk", "position": [0, 4, 2], "direction": [0, -1, -0.3],
                               "size": 1.5, "color": [3, 3, 3], "group": "panel"})
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(document))
    shaded = phongcl.Relighter(phongcl.load_scene(str(path)), gbuffer, terms=True).shade_terms()
    assert sorted(shaded["groups"]) == ["panel"]
    plain = phongcl.Relighter(scene, gbuffer, terms=True).shade_terms()
    image = shaded["image"]
    lit = image[..., 3] == 1
    total = (shaded["ambient"] + plain["diffuse"] + plain["specular"] + shaded["groups"]["panel"])[..., :3]
    np.testing.assert_allclose(total[lit], image[..., :3][lit], rtol=1e-5, atol=1e-6)
    assert (shaded["groups"]["panel"][lit] > 0).any()


@needs_device
def test_light_groups_come_back_apart_and_add_up(scene, gbuffer):
    grouped = phongcl.load_scene(str(DEFAULT))
    lights = grouped.lights
    assert len(lights) >= 2, "the default scene has two lights or more"
    lights[0].group = "key"
    lights[1].group = "fill"
    grouped.lights = lights
    relighter = phongcl.Relighter(grouped, gbuffer, terms=True)
    shaded = relighter.shade_terms()
    assert sorted(shaded["groups"]) == ["fill", "key"]
    image = shaded["image"]
    check_against_reference(image, scene, gbuffer, "grouped")
    key = phongcl.Relighter(grouped, gbuffer, terms=True)
    key.set_lights(lights[0:1])
    key_terms = key.shade_terms()
    np.testing.assert_allclose(shaded["groups"]["key"][..., :3], (key_terms["diffuse"] + key_terms["specular"])[..., :3],
                               rtol=1e-5, atol=1e-6)
    rest = phongcl.Relighter(grouped, gbuffer, terms=True)
    rest.set_lights(lights[2:])
    rest_terms = rest.shade_terms()
    total = (shaded["ambient"] + rest_terms["diffuse"] + rest_terms["specular"])[..., :3].astype(np.float64)
    for layer in shaded["groups"].values():
        total += layer[..., :3]
    lit = image[..., 3] == 1
    np.testing.assert_allclose(total[lit], image[..., :3][lit], rtol=1e-5, atol=1e-6)
    assert (shaded["groups"]["key"][lit] > 0).any()
    with pytest.raises(RuntimeError, match="terms"):
        phongcl.Relighter(grouped, gbuffer).shade_terms()
    lights[0].group = "k" * 64  # past Blender's 63 bytes; group.<name>.R must fit an EXR channel name
    with pytest.raises(ValueError, match="at most 63 bytes"):
        relighter.set_lights(lights)


def test_write_png_through_a_view_over_a_background(tmp_path):
    """The binding passes each setting on (the display transform itself is tested in C++):
    equal settings make equal files, and each setting changes the file."""
    image = np.zeros((2, 3, 4), dtype=np.float32)
    image[0, 0] = [0.2, 0.2, 0.2, 1.0]    # opaque
    image[0, 2] = [0.1, 0.1, 0.1, 0.5]    # half covered; the rest transparent
    doubled = image * np.array([2, 2, 2, 1], dtype=np.float32)

    def png(name, array, **settings):
        phongcl.write_png(str(tmp_path / name), array, **settings)
        return (tmp_path / name).read_bytes()

    base = png("a.png", image, view="clamp", background=(0.1, 0.1, 0.1), exposure=1.0)
    assert base[1:4] == b"PNG"
    assert png("b.png", doubled, view="clamp", background=(0.2, 0.2, 0.2)) == base   # exposure scales everything
    assert png("c.png", image, view="clamp", background=(0.3, 0.1, 0.1), exposure=1.0) != base
    assert png("d.png", image, view="aces", background=(0.1, 0.1, 0.1), exposure=1.0) != base
    with pytest.raises(phongcl.InputError, match="has no view 'Filmic'"):
        phongcl.write_png(str(tmp_path / "e.png"), image, view="Filmic")
    assert not (tmp_path / "e.png").exists()


def test_colors_lists_the_config():
    colors = phongcl.colors()
    assert colors["working_space"] == "Linear Rec.709 (sRGB)"
    assert colors["displays"] == {"sRGB": ["reinhard", "aces", "clamp"]}
    assert "ACEScg" in colors["color_spaces"]
    with pytest.raises(phongcl.InputError, match="cannot read the OCIO config"):
        phongcl.colors(ocio="/nonexistent/config.ocio")


def test_write_exr_is_black_where_transparent_unless_asked(tmp_path):
    image = np.full((1, 2, 4), 0.25, dtype=np.float32)
    image[0, 1, 3] = 0.0
    phongcl.write_exr(str(tmp_path / "a.exr"), image)
    phongcl.write_exr(str(tmp_path / "b.exr"), image, keep_color_where_transparent=True)
    assert list(phongcl.read_exr(str(tmp_path / "a.exr"))[0, 1]) == [0, 0, 0, 0]
    assert list(phongcl.read_exr(str(tmp_path / "b.exr"))[0, 1]) == [0.25, 0.25, 0.25, 0]


def test_scene_colours_in_a_named_space_arrive_in_the_working_space():
    scene = phongcl.Scene.from_dict({"color_space": "sRGB", "ambient": [0.5, 0.5, 0.5],
                                     "lights": [{"type": "point", "position": [0, 1, 0], "color": [1, 0.5, 0]}]})
    decoded = ((0.5 + 0.055) / 1.055) ** 2.4
    assert scene.ambient == pytest.approx([decoded] * 3, rel=1e-6)
    assert scene.lights[0].color == pytest.approx([1, decoded, 0], rel=1e-6)
    with pytest.raises(phongcl.InputError, match="no such colour space"):
        phongcl.Scene.from_dict({"color_space": "Rec.2020"})


@needs_device
def test_a_sequence_hands_each_frame_to_one_relighter(scene, gbuffer):
    relighter = phongcl.Relighter(scene, gbuffer)
    first = relighter.shade()
    document = json.loads(DEFAULT.read_text())
    document["lights"] = [{"type": "point", "position": [-3, 5, 4], "color": [1.2, 1, 0.8]}]
    moved = phongcl.Scene.from_dict(document)
    # The next frame: other lights, the image upside down, then a smaller one.
    flipped = phongcl.GBuffer(P=gbuffer.P[::-1], N=gbuffer.N[::-1], material=np.array(gbuffer.material)[::-1])
    cropped = phongcl.GBuffer(P=gbuffer.P[:40, :60], N=gbuffer.N[:40, :60],
                              material=np.array(gbuffer.material)[:40, :60])
    for frame_scene, frame in [(moved, flipped), (scene, cropped), (scene, gbuffer)]:
        relighter.set_frame(frame_scene, frame)
        np.testing.assert_array_equal(relighter.shade(), phongcl.Relighter(frame_scene, frame).shade())
    np.testing.assert_array_equal(relighter.shade(), first)
    # A frame the scene cannot shade is refused, and the one before stays.
    document["materials"] = document["materials"][:1]
    with pytest.raises(phongcl.InputError, match="material"):
        relighter.set_frame(phongcl.Scene.from_dict(document), gbuffer)  # the G-buffer uses indices up to 4
    np.testing.assert_array_equal(relighter.shade(), first)


@needs_device
def test_lights_read_from_a_relighter_stay_valid_across_edits(gbuffer):
    # The lists are copies: set_lights replacing the relighter's lights leaves them whole, so the same
    # list can be edited and sent again (they once pointed into the vector it replaced).
    relighter = phongcl.Relighter(phongcl.load_scene(str(DEFAULT)), gbuffer)
    lights = relighter.scene.lights
    for step in range(3):
        lights[0].position = [4.0 + step, 6.0, 5.0]
        relighter.set_lights(lights)
        assert lights[0].type == "point" and list(lights[0].position) == [4.0 + step, 6.0, 5.0]
        assert list(relighter.scene.lights[0].position) == [4.0 + step, 6.0, 5.0]
    scene = relighter.scene
    materials = scene.materials
    scene.materials = materials[:1]
    assert materials[0].name == scene.materials[0].name and len(materials) > 1


def test_shade_over_a_render_changes_only_the_edited_groups(tmp_path, gbuffer):
    # A "render" that phongcl made itself, passes written as Blender's: over it, no edit is the render, a
    # brighter group its pass scaled, and a moved light phongcl's own shading of the edit (the fit is 1).
    description = json.loads(DEFAULT.read_text())
    for light, group in zip(description["lights"], ["key", "fill", "rim"]):
        light["group"] = group
    description["rendered"] = {"lights": json.loads(json.dumps(description["lights"]))}
    description["gbuffer"] = str(DEFAULT_GBUFFER)
    scene = phongcl.Scene.from_dict(description)
    relighter = phongcl.Relighter(scene, gbuffer, terms=True)
    shaded = relighter.shade_terms()
    passes = {"ViewLayer.Combined": shaded["image"]}
    for name, layer in shaded["groups"].items():
        passes["ViewLayer.Combined_" + name] = layer[..., :3]
    render = tmp_path / "render.exr"
    phongcl.write_exr(str(render), passes, keep_color_where_transparent=True)
    np.testing.assert_array_equal(phongcl.read_exr(str(render), layer="ViewLayer.Combined"), shaded["image"])
    with pytest.raises(phongcl.InputError, match="missing channel ViewLayer.Diffuse.R"):
        phongcl.read_exr(str(render), layer="ViewLayer.Diffuse")

    same = relighter.shade_over(str(render))
    np.testing.assert_array_equal(same["image"], shaded["image"])
    assert {name: group["change"] for name, group in same["groups"].items()} == {
        "key": "unchanged", "fill": "unchanged", "rim": "unchanged"}

    lights = relighter.scene.lights
    lights[0].position = [lights[0].position[0] + 0.5, lights[0].position[1], lights[0].position[2]]
    lights[1].color = [2 * c for c in lights[1].color]
    relighter.set_lights(lights)
    over = relighter.shade_over(str(render))
    assert over["groups"]["key"]["change"] == "re-shaded"
    np.testing.assert_allclose(over["groups"]["key"]["diffuse_gain"], (1, 1, 1), rtol=1e-4)
    assert over["groups"]["fill"] == {"change": "scaled", "scale": (2.0, 2.0, 2.0)}
    np.testing.assert_allclose(over["image"], relighter.shade(), rtol=1e-5, atol=1e-6)

    with pytest.raises(phongcl.InputError, match="missing.exr"):
        relighter.shade_over(str(tmp_path / "missing.exr"))

    # Held for a loop of edits: the same composites, the render read once.
    compositor = phongcl.RenderCompositor(str(render))
    np.testing.assert_array_equal(compositor.relight(relighter)["image"], over["image"])
    lights[0].position = [lights[0].position[0] + 0.25, lights[0].position[1], lights[0].position[2]]
    relighter.set_lights(lights)
    np.testing.assert_allclose(compositor.relight(relighter)["image"], relighter.shade(), rtol=1e-5, atol=1e-6)
    with pytest.raises(phongcl.InputError, match="missing.exr"):
        phongcl.RenderCompositor(str(tmp_path / "missing.exr"))
