#!/usr/bin/env python3
"""The Relighter's figures at 1080p (scenes/large; generate its G-buffer first with
`build/phongcl gbuffer --scene scenes/large/scene.json`), in one run, round-robin so that the
machine's load falls on every contender alike:

  1. a light change + re-shade through Relighter (C++, bench_relighter) against the kernel time
     plus the download of the same frames (the Relighter's own profiling-event and copy times);
  2. that frame against a `phongcl shade` process for the same scene (read, pack, build from the
     disk cache, shade, write the EXR);
  3. the Python turntable loop (set_lights + shade(out=...)) against the same loop in C++.

Each round runs STEPS orbit frames in C++ and in Python and one `phongcl shade`; figures are medians
over every frame (or process) of every round.

    PYTHONPATH=build/python /usr/bin/python3 bench/relighter_benchmark.py [--rounds 5] [--steps 36]
"""
import argparse
import json
import math
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "examples"))
import phongcl  # noqa: E402
from relight_turntable import orbit  # noqa: E402  the same orbit as the example


def loadavg():
    return pathlib.Path("/proc/loadavg").read_text().split()[:3]


def python_loop(relighter, scene, steps, image):
    """Per frame: wall clock of set_lights + shade, and the Relighter's kernel + download within it."""
    frames, device = [], []
    for step in range(steps):
        start = time.perf_counter()
        relighter.set_lights(orbit(scene, step, steps))
        relighter.shade(out=image)
        frames.append(1000 * (time.perf_counter() - start))
        timings = relighter.last_timings
        device.append(timings["kernel_ms"] + timings["download_ms"])
    return frames, device


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "scenes/large/scene.json"))
    parser.add_argument("--gbuffer", default=str(ROOT / "scenes/large/gbuffer.exr"))
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--steps", type=int, default=36)
    parser.add_argument("--json", help="also write the raw figures here")
    args = parser.parse_args()
    build = pathlib.Path(args.build)
    if not pathlib.Path(args.gbuffer).exists():
        sys.exit(f"{args.gbuffer}: missing; run {build}/phongcl gbuffer --scene {args.scene}")

    start_load = loadavg()
    scene = phongcl.load_scene(args.scene)
    gb = phongcl.read_gbuffer(args.gbuffer)
    relighter = phongcl.Relighter(scene, gb)
    image = np.empty((gb.height, gb.width, 4), dtype=np.float32)
    relighter.shade(out=image)  # warm-up: build, upload, first touch

    cpp_frames, kernel_plus_download, python_frames, python_device, shade_processes = [], [], [], [], []
    with tempfile.TemporaryDirectory() as scratch:
        for _ in range(args.rounds):
            run = subprocess.run([str(build / "bench/bench_relighter"), args.scene, args.gbuffer, str(args.steps)],
                                 check=True, capture_output=True, text=True)
            cpp = json.loads(run.stdout)
            cpp_frames += cpp["frame_ms"]
            kernel_plus_download += [k + d for k, d in zip(cpp["kernel_ms"], cpp["download_ms"])]
            frames, device = python_loop(relighter, scene, args.steps, image)
            python_frames += frames
            python_device += device
            start = time.perf_counter()
            subprocess.run([str(build / "phongcl"), "shade", "--scene", args.scene, "--gbuffer", args.gbuffer,
                            "--out", str(pathlib.Path(scratch) / "frame.exr")], check=True, capture_output=True)
            shade_processes.append(1000 * (time.perf_counter() - start))

    median = statistics.median
    frame, bare, py, process = median(cpp_frames), median(kernel_plus_download), median(python_frames), median(
        shade_processes)
    print(f"Relighter at {gb.width}x{gb.height} ({len(scene.lights)} lights), {relighter.device}")
    print(f"  {args.rounds} rounds x {args.steps} frames; loadavg {' '.join(start_load)} -> {' '.join(loadavg())}")
    print(f"  light change + re-shade (C++)       {frame:8.2f} ms")
    print(f"  kernel + download of those frames   {bare:8.2f} ms   ratio {frame / bare:.2f}x (target <= 1.3x)")
    print(f"  phongcl shade process, same frame   {process:8.2f} ms   {process / frame:.1f}x slower (target >= 20x)")
    print(f"  Python turntable frame              {py:8.2f} ms   {py / frame:.3f}x the C++ loop (target within 10%)")
    print(f"    of which kernel + download        {median(python_device):8.2f} ms   "
          f"(Python's own overhead: {py - median(python_device):.2f} ms a frame; C++'s: {frame - bare:.2f} ms)")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps({
            "width": gb.width, "height": gb.height, "rounds": args.rounds, "steps": args.steps,
            "loadavg": [start_load, loadavg()], "cpp_frame_ms": cpp_frames,
            "kernel_plus_download_ms": kernel_plus_download, "python_frame_ms": python_frames, "python_kernel_plus_download_ms": python_device,
            "shade_process_ms": shade_processes}, indent=1))


if __name__ == "__main__":
    main()
