#!/usr/bin/env python3
"""Orbits a point light around a scene in N steps with phongcl.Relighter, writes a PNG per frame and
prints frames per second. The G-buffer stays on the device: each frame uploads two light tables,
runs the kernel and copies the image out.

    PYTHONPATH=build/python python3 examples/relight_turntable.py --scene scenes/large/scene.json --out out/turntable
"""
import argparse
import math
import pathlib
import time

import numpy as np

import phongcl


def orbit(scene, step, steps):
    """The scene's lights with the first point light moved to `step` of `steps` around the look-at
    point, at its original height and distance."""
    lights = list(scene.lights)
    first = next(i for i, light in enumerate(lights) if light.type == "point")
    centre = np.array(scene.camera.look_at)
    offset = np.array(lights[first].position) - centre
    radius = math.hypot(offset[0], offset[2])
    angle = math.atan2(offset[2], offset[0]) + 2 * math.pi * step / steps
    position = [centre[0] + radius * math.cos(angle), lights[first].position[1], centre[2] + radius * math.sin(angle)]
    lights[first] = phongcl.Light("point", position=position, color=lights[first].color)
    return lights


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="scenes/default/scene.json")
    parser.add_argument("--gbuffer", help="default: the scene's 'gbuffer' entry")
    parser.add_argument("--out", default="out/turntable", help="directory for frame_NN.png")
    parser.add_argument("--steps", type=int, default=36)
    parser.add_argument("--device", default=None)
    parser.add_argument("--no-png", action="store_true", help="only time the frames")
    args = parser.parse_args()

    scene = phongcl.load_scene(args.scene)
    gbuffer_path = args.gbuffer or str(pathlib.Path(args.scene).parent / "gbuffer.exr")
    gb = phongcl.read_gbuffer(gbuffer_path)
    relighter = phongcl.Relighter(scene, gb, device=args.device)
    relighter.shade()  # builds the kernel and uploads the G-buffer: not part of the frame rate
    out_dir = pathlib.Path(args.out)
    if not args.no_png:
        out_dir.mkdir(parents=True, exist_ok=True)

    image = np.empty((gb.height, gb.width, 4), dtype=np.float32)
    shading = 0.0
    start = time.perf_counter()
    for step in range(args.steps):
        frame_start = time.perf_counter()
        relighter.set_lights(orbit(scene, step, args.steps))
        relighter.shade(out=image)
        shading += time.perf_counter() - frame_start
        if not args.no_png:
            phongcl.write_png(str(out_dir / f"frame_{step:02d}.png"), image, background=scene.background)
    elapsed = time.perf_counter() - start
    print(f"relight_turntable: {args.steps} frames of {gb.width}x{gb.height} on {relighter.device}")
    print(f"  relight + shade  {args.steps / shading:.1f} frames/s ({1000 * shading / args.steps:.2f} ms a frame)")
    if not args.no_png:
        print(f"  with PNG writes  {args.steps / elapsed:.1f} frames/s; frames in {out_dir}/")


if __name__ == "__main__":
    main()
