#!/usr/bin/env bash
# The environment light against Cycles: renders scripts/blender/environment_scene.py (shadow_scene.py's
# spheres and box on a ground, pure diffuse, no bounces, lit by the world alone) under a uniform world and
# under an HDRI world (an equirectangular EXR turned by a Mapping node), at 160x120 and 256 samples per
# pixel, and for each:
#   1. the exported {"type": "environment"} light must be exactly what the world holds;
#   2. environment_reference.py must find Cycles' diffuse light where the map, its orientation and its
#      rotation say (brute force over the map, median within 1.5%: measured 0.3% to 0.8%; the rotation
#      20 degrees off is 8% to 10% off, its sign flipped 35%): the exporter's conventions, without phongcl;
#   3. phongcl shades it with --shadows geometry (the exported meshes, default rays), screen and off, and
#      `phongcl agreement` (Cycles' DiffDir x DiffCol within 5% of the unshadowed light, away from
#      silhouettes) must hold geometry >= 99% (docs/formats.md "The world"), and screen (the horizons of
#      kernels/environment_horizons.h) its measured level less a margin (94% and 93%: measured 96.2% and
#      95.2% on Blender 3.4, 4.3 and 5.2; docs/environment.md "Screen space: horizons").
# BLENDER=PATH checks another Blender (scripts/setup.sh blender4, blender5); PHONGCL_ENVIRONMENT_CHECK_SIZE
# ="320 240" and PHONGCL_ENVIRONMENT_CHECK_SAMPLES=N change the render; PHONGCL_ENVIRONMENT_CHECK_KEEP=DIR
# keeps the files. Needs build/phongcl and build/phongcl-lab (scripts/test.sh builds them first).
set -euo pipefail
cd "$(dirname "$0")/../.."
check=67-blender-environment
source scripts/checks/lib/environment_check.sh

agreement() {  # world directory, mode, --at-least percentage: prints the percentage
  "$phongcl" agreement --cycles "$1/render.exr" --shaded "$1/$2.aov.exr" --unshadowed "$1/off.aov.exr" --at-least "$3" \
    >"$1/agreement-$2.txt" || { cat "$1/agreement-$2.txt" >&2; echo "$check: $(basename "$1"), $2 below $3%" >&2; exit 1; }
  grep -o 'every light [0-9.]*%' "$1/agreement-$2.txt" | cut -d' ' -f3
}

summary=()
for world in uniform hdri; do
  dir="$work/$world"
  render_environment "$world"

  python3 - "$dir/scene.json" "$world" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
expected = {"uniform": {"type": "environment", "color": [0.6, 0.75, 1.0], "strength": 1.2, "shadows": True},
            "hdri": {"type": "environment", "file": "sky.exr", "rotation": 40.0, "strength": 1.5, "shadows": True}}[sys.argv[2]]
assert scene["lights"] == [expected], "exported %s, expected [%s]" % (scene["lights"], expected)
assert scene["ambient"] == [0, 0, 0], "an ambient term beside the environment: %s" % scene["ambient"]
assert len(scene["objects"]) == 5, "the ground, three spheres and a box expected as meshes: %s" % scene["objects"]
PY
  python3 scripts/blender/environment_reference.py --scene "$dir/scene.json" --render "$dir/render.exr" --tolerance 0.015 \
    >"$work/reference-$world.txt" ||
    { cat "$work/reference-$world.txt"; echo "$check: Cycles' $world light is not where the exported light puts it" >&2; exit 1; }
  reference=$(tail -1 "$work/reference-$world.txt" | sed 's/^environment_reference: //')

  for mode in geometry screen off; do
    "$phongcl" shade --scene "$dir/scene.json" --shadows "$mode" --out "$dir/$mode.exr" --aov "$dir/$mode.aov.exr" \
      >"$work/shade-$world-$mode.log" || { cat "$work/shade-$world-$mode.log"; echo "$check: shading $world ($mode) failed" >&2; exit 1; }
  done
  off=$(agreement "$dir" off 0)
  geometry=$(agreement "$dir" geometry 99)
  # Screen space sees only what the camera sees: held to its measured level less a margin (a uniform
  # world: 96.2%; the HDRI: 95.2%, its sun's shadow a march).
  screen=$(agreement "$dir" screen "$([ "$world" = uniform ] && echo 94 || echo 93)")
  summary+=("$world: $geometry geometry, $screen screen, $off unshadowed (reference: $reference)")
done
echo "$check: Cycles ${width}x${height}, $samples samples; $(IFS=';'; echo "${summary[*]}" | sed 's/;/; /g')"
