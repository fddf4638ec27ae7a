#!/usr/bin/env bash
# Relighting over the render against Cycles: renders scripts/blender/over_scene.py (Principled
# materials, shadows, two bounces, a grey world; a key point light, a fill area light and a rim spot in
# light groups of their own) at 160x120, 1024 samples, and Cycles' renders of two edits, then composites with
# `phongcl shade --over` and holds each to Cycles with `phongcl agreement` (pixels within 5%, away
# from silhouettes; docs/compositing.md):
#   no edit                 the render itself (relative error 0 everywhere);
#   the key at twice power  a scaled pass: as close to Cycles' seed-1 render as Cycles' own seed-0 render
#                           is (its noise), and 99.5% within 5% of the seed-0 render (Cycles 4.x samples
#                           lights by power, so even the same seed draws other paths);
#   the key moved 0.5 m     >= 97% within 5% of Cycles' render of the move (same seed), with the
#                           figures of the pure phongcl relight and of the render left as it was beside
#                           (99.0% on Blender 3.4, 98.3% on 4.3 and 5.2: docs/compositing.md).
# BLENDER=PATH checks another Blender; PHONGCL_OVER_CHECK_KEEP=DIR keeps the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=64-blender-over
keep="${PHONGCL_OVER_CHECK_KEEP:-}"
source scripts/checks/lib/blender_check.sh
fail() { echo "$check: FAILED: $*" >&2; exit 1; }

"$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/over_scene.py -- --out "$work" \
  >"$work/blender.log" 2>&1 || { tail -20 "$work/blender.log"; fail "over_scene.py"; }

python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
scene = json.load(open(work + "/scene.json"))
assert scene["rendered"]["lights"] == scene["lights"], "the exporter's rendered lights differ from its lights"
key = [light for light in scene["lights"] if light.get("group") == "key"]
assert len(key) == 1, "one light in group 'key' expected"
brighter = json.loads(json.dumps(scene))
for light in brighter["lights"]:
    if light.get("group") == "key":
        light["color"] = [2.0 * c for c in light["color"]]
json.dump(brighter, open(work + "/brighter.json", "w"), indent=1)
moved = json.loads(json.dumps(scene))
for light in moved["lights"]:
    if light.get("group") == "key":
        light["position"][0] += 0.5  # over_scene.MOVE
json.dump(moved, open(work + "/moved.json", "w"), indent=1)
PY

for edit in scene brighter moved; do
  "$phongcl" shade --scene "$work/$edit.json" --over "$work/render.exr" --out "$work/over-$edit.exr" >"$work/shade-$edit.log" ||
    { cat "$work/shade-$edit.log"; fail "shade --over ($edit)"; }
  "$phongcl" shade --scene "$work/$edit.json" --out "$work/phongcl-$edit.exr" >/dev/null || fail "shade ($edit)"
done
grep -q "key unchanged, rim unchanged, fill unchanged" "$work/shade-scene.log" || { cat "$work/shade-scene.log"; fail "no edit found"; }
grep -q "key scaled x(2, 2, 2)" "$work/shade-brighter.log" || { cat "$work/shade-brighter.log"; fail "the brighter key is not a scaled pass"; }
grep -q "key changed by phongcl's change (fit: " "$work/shade-moved.log" || { cat "$work/shade-moved.log"; fail "the moved key was not re-shaded"; }

agree() {  # cycles file, shaded file, shaded layer ('' for an --out image): the percentage within 5%
  "$phongcl" agreement --cycles "$1" --cycles-pass Combined --shaded "$2" --unshadowed "$2" --layer "$3" --tolerance 0.05 |
    grep -o 'every light [0-9.]*%' | cut -d' ' -f3 | tr -d %
}
at_least() { python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) else 1)" "$1" "$2"; }

"$phongcl" agreement --cycles "$work/render.exr" --cycles-pass Combined --shaded "$work/over-scene.exr" --layer '' \
  --median-at-most 0 --p99-at-most 0 >/dev/null || fail "with no edit, the composite is not the render"
noise=$(agree "$work/brighter1.exr" "$work/brighter0.exr" ViewLayer.Combined)
scaled=$(agree "$work/brighter1.exr" "$work/over-brighter.exr" '')
scaled_same_seed=$(agree "$work/brighter0.exr" "$work/over-brighter.exr" '')
at_least "$scaled" "$(python3 -c "print($noise - 0.5)")" || fail "the key at twice power: $scaled% against Cycles' own $noise%"
at_least "$scaled_same_seed" 99.5 || fail "the key at twice power: $scaled_same_seed% of the same seed's render"
moved=$(agree "$work/moved.exr" "$work/over-moved.exr" '')
pure=$(agree "$work/moved.exr" "$work/phongcl-moved.exr" '')
unchanged=$(agree "$work/moved.exr" "$work/render.exr" ViewLayer.Combined)
at_least "$moved" 97 || fail "the key moved 0.5 m: $moved% within 5% of Cycles' render (pure phongcl $pure%)"
echo "$check: Cycles 160x120, ${PHONGCL_OVER_SAMPLES:-1024} samples, 2 bounces; no edit: the render; key x2: $scaled% (Cycles' noise $noise%," \
  "same seed $scaled_same_seed%); key moved 0.5 m: $moved% (pure phongcl $pure%, render unchanged $unchanged%);" \
  "$(grep -o 'fit: .*, residual [0-9.e-]*' "$work/shade-moved.log")"
