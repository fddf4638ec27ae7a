#!/usr/bin/env bash
# A .blend to a relit EXR with the two commands of the README's "Shade your own render": builds a
# tiny scene in Blender (64x48), exports it and renders its G-buffer with Cycles (4 samples, CPU) through
# scripts/blender/export_scene.py, then shades it with phongcl, which must detect the Blender
# layout with no flags beyond --scene. Needs build/phongcl (scripts/test.sh builds it first).
set -euo pipefail
cd "$(dirname "$0")/../.."
phongcl="${PHONGCL_BUILD_DIR:-build}/phongcl"
[ -x "$phongcl" ] || { echo "60-blender: no $phongcl (build first)" >&2; exit 1; }
command -v blender >/dev/null || { echo "60-blender: blender is not installed (scripts/setup.sh blender)" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"

blender -b --factory-startup --python-expr "
import sys; sys.path.insert(0, 'scripts/blender')
import bpy, make_fixtures
make_fixtures.build_scene(64, 48)
bpy.ops.wm.save_as_mainfile(filepath='$work/tiny.blend')
" >"$work/blender.log" 2>&1 || { tail -20 "$work/blender.log"; echo "60-blender: building the .blend failed" >&2; exit 1; }

blender -b "$work/tiny.blend" --python scripts/blender/export_scene.py -- \
  --out "$work/scene.json" --render "$work/gbuffer.exr" --samples 4 >>"$work/blender.log" 2>&1 ||
  { tail -20 "$work/blender.log"; echo "60-blender: export_scene.py failed" >&2; exit 1; }

"$phongcl" shade --scene "$work/scene.json" --out "$work/lit.exr" >"$work/shade.log"
grep -q "layout     blender (view layer 'ViewLayer': Position, Normal" "$work/shade.log" ||
  { cat "$work/shade.log"; echo "60-blender: the Blender layout was not detected" >&2; exit 1; }
[ -s "$work/lit.exr" ] || { echo "60-blender: no output image" >&2; exit 1; }
echo "60-blender: exported, rendered (Cycles 64x48, 4 samples) and shaded: $(grep -o '[0-9,]* shaded' "$work/shade.log")"
