#!/usr/bin/env bash
# Light types against Cycles: renders scripts/blender/light_scene.py (two spots, one with a blend, a
# point light and a sun over spheres on a ground; pure diffuse, no bounces, no shadows) at 96x72,
# shades each light alone with --aov and holds phongcl's diffuse layer to Cycles' direct diffuse light
# (DiffDir x DiffCol) away from silhouettes: a median relative error <= 1e-3 and a 99th percentile
# <= 1e-2 for every light (docs/formats.md "Lights from Blender"). Needs build/phongcl and
# build/phongcl-lab (scripts/test.sh builds them first). PHONGCL_LIGHT_CHECK_KEEP=DIR keeps the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=62-blender-lights
build="${PHONGCL_BUILD_DIR:-build}"
phongcl="$build/phongcl"
[ -x "$phongcl" ] || { echo "$check: no $phongcl (build first)" >&2; exit 1; }
command -v blender >/dev/null || { echo "$check: blender is not installed (scripts/setup.sh blender)" >&2; exit 1; }

work="${PHONGCL_LIGHT_CHECK_KEEP:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"

blender -b --factory-startup --python scripts/blender/light_scene.py -- --out "$work" >"$work/blender.log" 2>&1 ||
  { tail -20 "$work/blender.log"; echo "$check: light_scene.py failed" >&2; exit 1; }

# One scene per light, the other lights removed (Cycles rendered each alone).
lights=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['lights']))" "$work/scene.json")
args=()
for ((k = 0; k < lights; ++k)); do
  python3 - "$work/scene.json" "$k" "$work/light$k.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["lights"] = [scene["lights"][int(sys.argv[2])]]
json.dump(scene, open(sys.argv[3], "w"), indent=1)
PY
  "$phongcl" shade --scene "$work/light$k.json" --out "$work/shaded$k.exr" --aov "$work/shaded$k.aov.exr" \
    >"$work/shade$k.log" || { cat "$work/shade$k.log"; echo "$check: shading light $k failed" >&2; exit 1; }
  args+=(--cycles "$work/light$k.exr" --shaded "$work/shaded$k.aov.exr")
done
"$phongcl" agreement "${args[@]}" --median-at-most 1e-3 --p99-at-most 1e-2 | tee "$work/agreement.txt"
echo "$check: Cycles 96x72, $lights lights alone, diffuse within median 1e-3 and p99 1e-2 of Cycles' direct diffuse"
