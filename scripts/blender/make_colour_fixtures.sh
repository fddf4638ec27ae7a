#!/usr/bin/env bash
# Makes the colour fixtures of tests/fixtures/colour/ (tests/test_color.cpp holds phongcl's display
# transforms to them without running Blender; scripts/checks/63-blender-colour.sh does the same at
# full size with a fresh Blender):
#   lit.exr          scenes/default shaded by phongcl at 320x240 (half, premultiplied, RGB 0 where
#                    alpha is 0)
#   blender/NAME.png Blender's own PNG of lit.exr over the scene's background for every case of
#                    cases.txt (scripts/blender/display_reference.py)
#     scripts/blender/make_colour_fixtures.sh      # needs build/phongcl and blender
set -euo pipefail
cd "$(dirname "$0")/../.."
phongcl="${PHONGCL_BUILD_DIR:-build}/phongcl"
out=tests/fixtures/colour
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$work/scene.json" <<'PY'
import json, sys
scene = json.load(open("scenes/default/scene.json"))
scene["camera"]["width"], scene["camera"]["height"] = 320, 240
del scene["gbuffer"]
json.dump(scene, open(sys.argv[1], "w"), indent=1)
PY
"$phongcl" gbuffer --scene "$work/scene.json" --out "$work/gbuffer.exr" >/dev/null
"$phongcl" shade --scene "$work/scene.json" --gbuffer "$work/gbuffer.exr" --out "$out/lit.exr" --half --compression zip >/dev/null
rm -rf "$out/blender"
background=$(/usr/bin/python3 -c "import json; print(','.join(map(str, json.load(open('$work/scene.json'))['background'])))")
blender -b --factory-startup --python scripts/blender/display_reference.py -- --exr "$out/lit.exr" \
  --background "$background" --cases "$out/cases.txt" --out "$out/blender" | grep '^display_reference'
