#!/usr/bin/env bash
# Area lights against Cycles: renders scripts/blender/area_scene.py (a ground under a rectangle and
# a disk area light; pure diffuse, no bounces, light threshold 0, pixel centres) at 96x72, shades each light alone, and holds `phongcl agreement` (Cycles' direct
# diffuse light, DiffDir x DiffCol, away from silhouettes) to the targets of docs/shading.md "Area
# lights": a median relative error <= 1e-3 (half the pixels within 1e-3) and a 99th percentile <=
# 1e-2 (99% within 1e-2). Cycles samples area lights: PHONGCL_AREA_CHECK_SAMPLES (default 1024) sets
# its samples per pixel, PHONGCL_AREA_CHECK_KEEP=DIR keeps the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=62-blender-area
keep="${PHONGCL_AREA_CHECK_KEEP:-}"
source scripts/checks/lib/blender_check.sh
samples="${PHONGCL_AREA_CHECK_SAMPLES:-1024}"

"$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/area_scene.py -- --out "$work" --samples "$samples" \
  >"$work/blender.log" 2>&1 || { tail -20 "$work/blender.log"; echo "$check: area_scene.py failed" >&2; exit 1; }

summary=""
for k in 0 1; do
  python3 - "$work/scene.json" "$k" "$work/light$k.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
area = [light for light in scene["lights"] if light["type"] == "area"]
assert len(area) == 2, "the exporter wrote %d area lights, not 2" % len(area)
scene["lights"] = [area[int(sys.argv[2])]]
json.dump(scene, open(sys.argv[3], "w"), indent=1)
PY
  "$phongcl" shade --scene "$work/light$k.json" --out "$work/shaded$k.exr" --aov "$work/shaded$k.aov.exr" \
    >"$work/shade$k.log" || { cat "$work/shade$k.log"; echo "$check: shading light $k failed" >&2; exit 1; }
  grep -q "area" "$work/shade$k.log" || { cat "$work/shade$k.log"; echo "$check: no area light in the summary" >&2; exit 1; }
  agree=(--cycles "$work/light$k.exr" --shaded "$work/shaded$k.aov.exr" --unshadowed "$work/shaded$k.aov.exr")
  "$phongcl" agreement "${agree[@]}" --tolerance 1e-3 --at-least 50 | tee "$work/median$k.txt"
  "$phongcl" agreement "${agree[@]}" --tolerance 1e-2 --at-least 99 | tee "$work/p99$k.txt"
  name=$([ "$k" = 0 ] && echo rect || echo disk)
  summary+=" $name $(grep -o 'every light [0-9.]*%' "$work/median$k.txt" | cut -d' ' -f3) within 1e-3,"
  summary+=" $(grep -o 'every light [0-9.]*%' "$work/p99$k.txt" | cut -d' ' -f3) within 1e-2;"
done
echo "$check: Cycles 96x72, $samples samples;$summary"
