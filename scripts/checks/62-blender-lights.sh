#!/usr/bin/env bash
# Light types and light groups against Cycles: renders scripts/blender/light_scene.py (two spots, one
# with a blend, a point light and a sun over spheres on a ground; pure diffuse, no bounces, no
# shadows; each light but the sun in a light group of its own) at 96x72, shades each light alone with
# --aov and holds phongcl's diffuse layer to Cycles' direct diffuse light (DiffDir x DiffCol), then
# shades them all and holds each group.<name> layer to Cycles' light group pass (Combined_<name>) of
# its light's render, away from silhouettes: a median relative error <= 1e-3 and a 99th percentile
# <= 1e-2 each (docs/formats.md "Blender"). Needs build/phongcl and build/phongcl-lab (scripts/test.sh
# builds them first). PHONGCL_LIGHT_CHECK_KEEP=DIR keeps the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=62-blender-lights
keep="${PHONGCL_LIGHT_CHECK_KEEP:-}"
source scripts/checks/lib/blender_check.sh

"$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/light_scene.py -- --out "$work" >"$work/blender.log" 2>&1 ||
  { tail -20 "$work/blender.log"; echo "$check: light_scene.py failed" >&2; exit 1; }

# One scene per light, the other lights removed (Cycles rendered each alone), and "all.json" with
# every light. The surfaces are pure diffuse: ks = 0 (the exporter's ks for a Diffuse BSDF is a guess),
# so that a group layer, diffuse + specular, is Cycles' Combined light of the group.
lights=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['lights']))" "$work/scene.json")
python3 - "$work" "$lights" <<'PY'
import json, sys
work, lights = sys.argv[1], int(sys.argv[2])
scene = json.load(open(work + "/scene.json"))
for material in scene["materials"]:
    material["ks"] = [0, 0, 0]
json.dump(scene, open(work + "/all.json", "w"), indent=1)
everything = scene["lights"]
for k in range(lights):
    scene["lights"] = [everything[k]]
    json.dump(scene, open("%s/light%d.json" % (work, k), "w"), indent=1)
PY
args=()
for ((k = 0; k < lights; ++k)); do
  "$phongcl" shade --scene "$work/light$k.json" --out "$work/shaded$k.exr" --aov "$work/shaded$k.aov.exr" \
    >"$work/shade$k.log" || { cat "$work/shade$k.log"; echo "$check: shading light $k failed" >&2; exit 1; }
  args+=(--cycles "$work/light$k.exr" --shaded "$work/shaded$k.aov.exr")
done
"$phongcl" agreement "${args[@]}" --median-at-most 1e-3 --p99-at-most 1e-2 | tee "$work/agreement.txt"

"$phongcl" shade --scene "$work/all.json" --out "$work/all.exr" --aov "$work/all.aov.exr" >"$work/shade-all.log" ||
  { cat "$work/shade-all.log"; echo "$check: shading every light failed" >&2; exit 1; }
groups=0
for ((k = 0; k < lights; ++k)); do
  group=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['lights'][0].get('group', ''))" "$work/light$k.json")
  [ -n "$group" ] || continue
  "$phongcl" agreement --cycles "$work/light$k.exr" --cycles-pass "Combined_$group" --shaded "$work/all.aov.exr" \
    --layer "group.$group" --median-at-most 1e-3 --p99-at-most 1e-2 | tee -a "$work/agreement.txt"
  groups=$((groups + 1))
done
[ "$groups" -ge 3 ] || { echo "$check: $groups light groups exported, 3 expected" >&2; exit 1; }
echo "$check: Cycles 96x72, $lights lights alone and $groups light groups within median 1e-3 and p99 1e-2 of Cycles"
