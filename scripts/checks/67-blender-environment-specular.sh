#!/usr/bin/env bash
# The environment light's specular against Cycles: renders scripts/blender/environment_scene.py with
# --materials principled (a rough dielectric ground, a glossier red, a blue metal; no bounces, lit by the
# world alone) under the uniform world and the HDRI world, at 160x120 and 256 samples per pixel, shades it
# with --shadows geometry (default rays) and holds `phongcl agreement --glossy` (phongcl's specular layer
# against Cycles' GlossDir x GlossCol, on the pixels where the glossy light is >= 20% of the direct light,
# away from silhouettes) to a median relative error of 5% under both worlds (the issue's target; measured
# 3.3% and 4.4% on 3.4, docs/environment.md "Specular"), printing the 99th percentile too.
# BLENDER=PATH checks another Blender (scripts/setup.sh blender4, blender5); PHONGCL_ENVIRONMENT_CHECK_SIZE
# ="320 240" and PHONGCL_ENVIRONMENT_CHECK_SAMPLES=N change the render; PHONGCL_ENVIRONMENT_CHECK_KEEP=DIR
# keeps the files. Needs build/phongcl and build/phongcl-lab (scripts/test.sh builds them first).
set -euo pipefail
cd "$(dirname "$0")/../.."
check=67-blender-environment-specular
source scripts/checks/lib/environment_check.sh

summary=()
for world in uniform hdri; do
  dir="$work/$world"
  render_environment "$world" --materials principled
  python3 - "$dir/scene.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
models = sorted({m.get("specular_model", "phong") for m in scene["materials"]})
assert models == ["principled"], "the materials should export as Principled: %s" % models
PY
  "$phongcl" shade --scene "$dir/scene.json" --shadows geometry --out "$dir/geometry.exr" --aov "$dir/geometry.aov.exr" \
    >"$work/shade-$world.log" || { cat "$work/shade-$world.log"; echo "$check: shading $world failed" >&2; exit 1; }
  "$phongcl" agreement --cycles "$dir/render.exr" --shaded "$dir/geometry.aov.exr" --layer specular --glossy \
    --median-at-most 0.05 >"$work/agreement-$world.txt" ||
    { cat "$work/agreement-$world.txt" >&2; echo "$check: $world: specular median beyond 0.05" >&2; exit 1; }
  summary+=("$world: $(grep -o 'median [0-9.e-]*, 99th percentile [0-9.e-]*' "$work/agreement-$world.txt")")
done
echo "$check: Cycles ${width}x${height}, $samples samples; $(IFS=';'; echo "${summary[*]}" | sed 's/;/; /g')"
