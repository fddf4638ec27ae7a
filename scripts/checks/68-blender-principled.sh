#!/usr/bin/env bash
# The Principled BSDF against Cycles: renders scripts/blender/principled_scene.py (Principled spheres of
# roughness 0.15 to 0.6, a metal, specular 0.5 and 1.0, on a Principled floor; a point, a spot and a sun
# light without size or shadows; no bounces) at 160x120 twice, with two seeds, each pixel's centre (a
# Gaussian filter of 0.01 px, as phongcl shades), exports it, shades each
# light alone with --aov, and holds with `phongcl-lab agreement` (docs/shading.md "Principled"):
#   - phongcl's specular layer against GlossDir x GlossCol on the pixels where the glossy light is >= 20%
#     of the direct light: median relative error <= 2%, 99th percentile <= 10%;
#   - the diffuse layer against DiffDir x DiffCol: median <= 2%, 99th percentile <= 10%;
#   - Cycles' own noise: both figures again against the render with the other seed, side by side;
#   - a rect and a disk area light (the same scene with --area, Cycles sampling them: 256 samples),
#     the specular layer against GlossDir x GlossCol on the same pixels, held as above (the LTC
#     highlight, docs/shading.md "Principled under area lights": medians 0.44% and 0.15%, 99th
#     percentiles 4.9% and 2.6% on 3.4 and 5.2; the reference's exact integral 1e-4 from Cycles),
#     reported beside the reference's; the diffuse (Burley's and Oren-Nayar's as Lambert's times a
#     ratio) reported only.
# On Blender 4.0+ the node is version 2 (docs/shading.md "Principled v2"), held to the same targets.
# Needs build/phongcl and build/phongcl-lab. PHONGCL_PRINCIPLED_CHECK_KEEP=DIR keeps the files;
# PHONGCL_PRINCIPLED_AREA_SAMPLES sets the area renders' samples.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=68-blender-principled
keep="${PHONGCL_PRINCIPLED_CHECK_KEEP:-}"
source scripts/checks/lib/blender_check.sh
lab="${PHONGCL_BUILD_DIR:-build}/phongcl-lab"
[ -x "$lab" ] || { echo "$check: no $lab (build first)" >&2; exit 1; }
release=$("$blender" --version 2>/dev/null | sed -n 's/^Blender \([0-9]*\.[0-9]*\).*/\1/p' | head -1)
mkdir -p "$work/seed1" "$work/area" "$work/area/seed1"

render() {  # directory, then principled_scene.py's options
  local dir=$1; shift
  for seed in 0 1; do
    out="$dir"; [ "$seed" = 0 ] || out="$dir/seed1"
    "$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/principled_scene.py -- --out "$out" \
      --seed "$seed" "$@" >"$out/blender.log" 2>&1 || { tail -20 "$out/blender.log"; echo "$check: principled_scene.py failed" >&2; exit 1; }
  done
}
render "$work"
render "$work/area" --area --samples "${PHONGCL_PRINCIPLED_AREA_SAMPLES:-256}"

shade_each_light() {  # directory: fills cycles, shaded and other with each light's files
  local dir=$1
  lights=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['lights']))" "$dir/scene.json")
  cycles=() shaded=() other=()
  for ((k = 0; k < lights; ++k)); do
    python3 - "$dir/scene.json" "$k" "$dir/light$k.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["lights"] = [scene["lights"][int(sys.argv[2])]]
json.dump(scene, open(sys.argv[3], "w"), indent=1)
PY
    # kd from the table, not from DiffCol: the material's own diffuse weight is what is held.
    "$phongcl" shade --scene "$dir/light$k.json" --kd-from table --out "$dir/shaded$k.exr" --aov "$dir/shaded$k.aov.exr" \
      >"$dir/shade$k.log" || { cat "$dir/shade$k.log"; echo "$check: shading light $k failed" >&2; exit 1; }
    cycles+=(--cycles "$dir/light$k.exr") shaded+=(--shaded "$dir/shaded$k.aov.exr") other+=(--cycles "$dir/seed1/light$k.exr")
  done
}

compare() {  # name, "held" or "report", then agreement's arguments
  local name=$1 kind=$2; shift 2
  local limits=(--median-at-most 0.02 --p99-at-most 0.10)
  [ "$kind" = held ] || limits=(--median-at-most 1e9)
  "$lab" agreement "$@" "${limits[@]}" | tee "$work/$name.txt" || { echo "$check: $name beyond its target" >&2; exit 1; }
}
shade_each_light "$work"
compare specular held "${cycles[@]}" "${shaded[@]}" --layer specular --glossy
compare diffuse held "${cycles[@]}" "${shaded[@]}" --layer diffuse
compare specular-seed1 held "${other[@]}" "${shaded[@]}" --layer specular --glossy
compare diffuse-seed1 held "${other[@]}" "${shaded[@]}" --layer diffuse
shade_each_light "$work/area"
# The LTC is held on both versions; the double reference's own exact integral beside it separates the
# highlight's error from Cycles' noise and sampling.
references=()
for ((k = 0; k < lights; ++k)); do
  "$lab" reference --scene "$work/area/light$k.json" --kd-from table --aov "$work/area/reference$k.aov.exr" \
    >"$work/area/reference$k.log" || { cat "$work/area/reference$k.log"; echo "$check: the reference of light $k failed" >&2; exit 1; }
  references+=(--shaded "$work/area/reference$k.aov.exr")
done
compare area-specular held "${cycles[@]}" "${shaded[@]}" --layer specular --glossy
compare area-reference-specular report "${cycles[@]}" "${references[@]}" --layer specular --glossy
compare area-diffuse report "${cycles[@]}" "${shaded[@]}" --layer diffuse
compare area-specular-seed1 held "${other[@]}" "${shaded[@]}" --layer specular --glossy
compare area-diffuse-seed1 report "${other[@]}" "${shaded[@]}" --layer diffuse
echo "$check: Blender $release, 160x120, point, spot and sun lights (held), then a rect and a disk (specular held)"
for name in specular diffuse specular-seed1 diffuse-seed1 area-specular area-reference-specular area-diffuse area-specular-seed1 area-diffuse-seed1; do
  echo "  $name: $(grep -o 'median [0-9.e-]*, 99th percentile [0-9.e-]* over [0-9]* lit pixels' "$work/$name.txt" | tr '\n' ';')"
done
