#!/usr/bin/env bash
# phongcl's PNGs against Blender's own from the same EXR, through Blender's OCIO config: the default
# scene (640x480, a coloured background) and the Cycles fixture (64x48, partly covered edge pixels)
# shaded to EXR by phongcl; Blender's compositor lays each over the scene's background and writes a
# PNG for every case of tests/fixtures/colour/cases.txt (Standard and Filmic, every look, exposures:
# scripts/blender/display_reference.py), or of cases-agx.txt for a Blender 4 or newer (AgX and its
# looks, Khronos PBR Neutral); `phongcl png` writes the same EXR through the same view of the same
# Blender's config (--blender), and at least 99.9% of the pixels must agree within 1/255. Prints the
# figures per case. BLENDER=PATH checks another Blender (scripts/setup.sh blender4, blender5): 5.x's
# config is for a newer OpenColorIO than Debian 12's, which reads what it can run of it (docs/colour.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
check=63-blender-colour
source scripts/checks/lib/blender_check.sh
blender=$(command -v "$blender")
version=$("$blender" --version 2>/dev/null | sed -n 's/^Blender \([0-9]*\)\..*/\1/p' | head -1)
cases=tests/fixtures/colour/cases.txt
[ "${version:-0}" -lt 4 ] || cases=tests/fixtures/colour/cases-agx.txt
fail() { echo "63-blender-colour: FAILED: $*" >&2; exit 1; }

trim() { local text=$1; text=${text#"${text%%[![:space:]]*}"}; echo "${text%"${text##*[![:space:]]}"}"; }

background_of() {  # the scene's "background" as r,g,b
  /usr/bin/python3 -c "import json, sys; print(','.join(str(v) for v in json.load(open(sys.argv[1])).get('background', [0, 0, 0])))" "$1"
}

check_frame() {  # name, scene, G-buffer
  local name=$1 scene=$2 gbuffer=$3 background
  background=$(background_of "$scene")
  "$phongcl" shade --scene "$scene" --gbuffer "$gbuffer" --out "$work/$name.exr" >"$work/$name-shade.log" ||
    { cat "$work/$name-shade.log"; fail "shading $name"; }
  "$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/display_reference.py -- --exr "$work/$name.exr" \
    --background "$background" --cases "$cases" --out "$work/$name-blender" >"$work/$name-blender.log" 2>&1 ||
    { tail -20 "$work/$name-blender.log"; fail "Blender's PNGs of $name"; }
  grep -v '^\s*\(#\|$\)' "$cases" | while IFS='|' read -r case view look exposure; do
    case=$(trim "$case"); view=$(trim "$view"); look=$(trim "$look"); exposure=$(trim "$exposure")
    "$phongcl" png "$work/$name.exr" "$work/$name-$case.png" --ocio blender --blender "$blender" --view "$view" --look "$look" \
      --exposure "$exposure" --background ${background//,/ } >/dev/null || fail "phongcl png $name $case"
    "$phongcl" compare "$work/$name-$case.png" "$work/$name-blender/$case.png" --bytes 1 --min-fraction 0.999 \
      >"$work/compare.log" 2>&1 || { cat "$work/compare.log"; fail "$name $case differs from Blender's PNG"; }
    printf '63-blender-colour: %-10s %-26s identical %8s, within 1/255 %8s, worst %s\n' "$name" "$case" \
      "$(sed -n 's/^  identical  //p' "$work/compare.log")" "$(sed -n 's/^  within 1\/255 //p' "$work/compare.log")" \
      "$(sed -n 's/^  worst      \([0-9]*\)\/255.*/\1/p' "$work/compare.log")"
  done
}

check_frame default scenes/default/scene.json scenes/default/gbuffer.exr
check_frame cycles tests/fixtures/blender/scene.json tests/fixtures/blender/cycles.exr
echo "63-blender-colour: every case of $(basename "$cases") within 1/255 of Blender $version on at least 99.9% of the pixels"
