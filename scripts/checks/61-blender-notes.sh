#!/usr/bin/env bash
# Nothing the exporter cannot map is dropped silently: scripts/blender/unmappable_scene.py exports a scene
# with an HDRI world, an ellipse area light, an emitting, texture-fed Principled BSDF and a Glass BSDF,
# and each must have its note, naming the object, the node and what was exported instead; the exported
# values must be what the notes say, and a spot's radius its "radius". No render (seconds).
# BLENDER=PATH checks another Blender (scripts/setup.sh blender4, blender5).
set -euo pipefail
cd "$(dirname "$0")/../.."
check=61-blender-notes
source scripts/checks/lib/blender_check.sh

"$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/unmappable_scene.py -- --out "$work/scene.json" \
  >"$work/blender.log" 2>&1 || { tail -20 "$work/blender.log"; echo "$check: unmappable_scene.py failed" >&2; exit 1; }

expect() {
  grep -qF "export_scene: $1" "$work/blender.log" ||
    { grep "export_scene:" "$work/blender.log"; echo "$check: no note \"$1\"" >&2; exit 1; }
}
expect "world 'World': Background's Color is fed by 'Environment Texture' (ShaderNodeTexEnvironment), which phongcl cannot evaluate: exported the socket's own value [0.05, 0.05, 0.06]"
expect "area light 'oval' is an ellipse, which phongcl has not: skipped, no light exported for it"
expect "material 'red': Principled BSDF's Base Color is fed by 'Noise Texture' (ShaderNodeTexNoise), which phongcl cannot evaluate: exported the socket's own value [0.8, 0.1, 0.1]"
expect "material 'red': the Principled BSDF emits light, which phongcl's materials do not: emission left out"
expect "material 'blue': its surface shader 'Glass BSDF' (ShaderNodeBsdfGlass) is neither a Principled nor a Diffuse BSDF: exported its viewport colour, no specular"

python3 - "$work/scene.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
assert scene["ambient"] == [0.05, 0.05, 0.06], scene["ambient"]
kinds = [light["type"] for light in scene["lights"]]
assert kinds.count("area") == 1, "the ellipse was exported: %s" % kinds
spot = next(light for light in scene["lights"] if light["type"] == "spot")
assert spot["radius"] == 0.25, spot
red, blue = scene["materials"][1], scene["materials"][2]
assert red.get("base_color", red.get("kd")) == [0.8, 0.1, 0.1], red  # 3.x: principled; 4.0+: Blinn-Phong
assert blue["ks"] == [0, 0, 0] and blue["kd"] == [0.8, 0.8, 0.8], blue
PY
echo "$check: $(grep -c '^export_scene: ' "$work/blender.log") notes, each unmappable feature named"
