#!/usr/bin/env python3
"""docs/compositing.md's side-by-side figure, from the files scripts/checks/64-blender-over.sh keeps
(PHONGCL_OVER_CHECK_KEEP=DIR): the render, the key moved 0.5 m composited over it, phongcl's own relight
of the move, and Cycles' render of the move, left to right, each scaled up `--scale` times (nearest
pixel), through one OCIO view.

    PHONGCL_OVER_CHECK_KEEP=/tmp/over bash scripts/checks/64-blender-over.sh
    PYTHONPATH=build/python /usr/bin/python3 scripts/dev/compositing-figure.py /tmp/over docs/compositing-move.png
"""
import argparse
import os

import numpy as np
import phongcl

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("kept", help="the folder 64-blender-over.sh kept")
parser.add_argument("out", help="the PNG to write")
parser.add_argument("--scale", type=int, default=3)
parser.add_argument("--view", default="Filmic", help="a view of Blender's OCIO config")
parser.add_argument("--gap", type=int, default=4, help="pixels of background between the pictures")
args = parser.parse_args()

pictures = [phongcl.read_exr(os.path.join(args.kept, "render.exr"), layer="ViewLayer.Combined"),
            phongcl.read_exr(os.path.join(args.kept, "over-moved.exr")),
            phongcl.read_exr(os.path.join(args.kept, "phongcl-moved.exr")),
            phongcl.read_exr(os.path.join(args.kept, "moved.exr"), layer="ViewLayer.Combined")]
height = pictures[0].shape[0]
gap = np.zeros((height, args.gap, 4), np.float32)
row = np.concatenate([part for picture in pictures for part in (picture, gap)][:-1], axis=1)
row = np.repeat(np.repeat(row, args.scale, axis=0), args.scale, axis=1)
phongcl.write_png(args.out, np.ascontiguousarray(row), view=args.view, ocio="blender")
print(f"{args.out}: render | composite of the move | phongcl's relight of the move | Cycles' move, "
      f"{row.shape[1]}x{row.shape[0]}, view {args.view}")
