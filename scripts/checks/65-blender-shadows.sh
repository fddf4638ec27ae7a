#!/usr/bin/env bash
# Shadows against Cycles: renders scripts/blender/shadow_scene.py (spheres and a box on a ground
# under two point lights that cast hard shadows; pure diffuse, no bounces) at 160x120, exports its
# meshes (export_scene.py --geometry), shades each light alone with --shadows geometry, screen and
# off, and holds `phongcl agreement` (Cycles' direct diffuse light, within 5% of each light's
# unshadowed value, away from silhouettes) to the targets of docs/shadows.md: geometry >= 99.5%,
# screen >= 96%. Needs build/phongcl and build/phongcl-lab (scripts/test.sh builds them first).
# PHONGCL_SHADOW_CHECK_SIZE="320 240" renders the docs' size; PHONGCL_SHADOW_CHECK_KEEP=DIR keeps the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
build="${PHONGCL_BUILD_DIR:-build}"
phongcl="$build/phongcl"
[ -x "$phongcl" ] || { echo "65-blender-shadows: no $phongcl (build first)" >&2; exit 1; }
blender="${BLENDER:-blender}"  # BLENDER=/var/cache/phongcl/bin/blender5 checks another version (scripts/setup.sh blender5)
command -v "$blender" >/dev/null || { echo "65-blender-shadows: $blender is not installed (scripts/setup.sh blender)" >&2; exit 1; }
read -r width height <<<"${PHONGCL_SHADOW_CHECK_SIZE:-160 120}"

work="${PHONGCL_SHADOW_CHECK_KEEP:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"

"$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/shadow_scene.py -- --out "$work" --width "$width" \
  --height "$height" >"$work/blender.log" 2>&1 ||
  { tail -20 "$work/blender.log"; echo "65-blender-shadows: shadow_scene.py failed" >&2; exit 1; }

# One scene per light, the other lights removed (Cycles rendered each alone).
lights=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['lights']))" "$work/scene.json")
for ((k = 0; k < lights; ++k)); do
  python3 - "$work/scene.json" "$k" "$work/light$k.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["lights"] = [scene["lights"][int(sys.argv[2])]]
json.dump(scene, open(sys.argv[3], "w"), indent=1)
PY
  for mode in geometry screen off; do
    "$phongcl" shade --scene "$work/light$k.json" --shadows "$mode" --out "$work/$mode$k.exr" \
      --aov "$work/$mode$k.aov.exr" >"$work/shade-$mode$k.log" ||
      { cat "$work/shade-$mode$k.log"; echo "65-blender-shadows: shading light $k ($mode) failed" >&2; exit 1; }
  done
done

agreement() {  # mode, --at-least percentage
  local args=()
  for ((k = 0; k < lights; ++k)); do
    args+=(--cycles "$work/light$k.exr" --shaded "$work/$1$k.aov.exr" --unshadowed "$work/off$k.aov.exr")
  done
  "$phongcl" agreement "${args[@]}" --at-least "$2" | tee "$work/agreement-$1.txt"
}
agreement off 0
agreement geometry 99.5
agreement screen 96
echo "65-blender-shadows: Cycles ${width}x${height}; every light agrees on" \
  "$(grep -o 'every light [0-9.]*%' "$work/agreement-off.txt" | cut -d' ' -f3) without shadows," \
  "$(grep -o 'every light [0-9.]*%' "$work/agreement-geometry.txt" | cut -d' ' -f3) geometry," \
  "$(grep -o 'every light [0-9.]*%' "$work/agreement-screen.txt" | cut -d' ' -f3) screen"
