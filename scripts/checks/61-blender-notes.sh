#!/usr/bin/env bash
# Nothing the exporter cannot map is dropped silently: scripts/blender/unmappable_scene.py exports a scene
# with a Sky Texture world, an ellipse area light, an emitting, transmitting, texture-fed Principled BSDF and a Glass BSDF,
# and each must have its note, naming the object, the node and what was exported instead; the exported
# values must be what the notes say, and a spot's radius its "radius". Then (--hdri) a world lit by a generated
# image through a Texture-type Mapping: its EXR copy holds the image's pixels, its rotation is negated and the
# Mapping's X rotation and scale are named. No render (seconds).
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
expect "world 'World': Background's Color is fed by 'Sky Texture' (ShaderNodeTexSky), which phongcl cannot evaluate: exported the socket's own value [0.05, 0.05, 0.06]"
expect "area light 'oval' is an ellipse, which phongcl has not: skipped, no light exported for it"
expect "material 'red': Principled BSDF's Base Color is fed by 'Noise Texture' (ShaderNodeTexNoise), which phongcl cannot evaluate: exported the socket's own value [0.8, 0.1, 0.1]"
expect "material 'red': the Principled BSDF emits light, which phongcl's materials do not: emission left out"
transmission=Transmission
"$blender" --version 2>/dev/null | grep -q '^Blender [4-9]' && transmission="Transmission Weight"
expect "material 'red': the Principled BSDF's $transmission is 0.5, which phongcl's principled material has not: left out"
expect "material 'blue': its surface shader 'Glass BSDF' (ShaderNodeBsdfGlass) is neither a Principled nor a Diffuse BSDF: exported its viewport colour, no specular"

python3 - "$work/scene.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
assert scene["ambient"] == [0, 0, 0], "the world is the environment light, not an ambient term: %s" % scene["ambient"]
world = [light for light in scene["lights"] if light["type"] == "environment"]
assert world == [{"type": "environment", "color": [0.05, 0.05, 0.06], "strength": 1, "shadows": True}], world
kinds = [light["type"] for light in scene["lights"]]
assert kinds.count("area") == 1, "the ellipse was exported: %s" % kinds
spot = next(light for light in scene["lights"] if light["type"] == "spot")
assert spot["radius"] == 0.25, spot
red, blue = scene["materials"][1], scene["materials"][2]
assert red["specular_model"] == "principled" and red["base_color"] == [0.8, 0.1, 0.1], red  # version 1 or 2
assert blue["ks"] == [0, 0, 0] and blue["kd"] == [0.8, 0.8, 0.8], blue
PY
"$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/unmappable_scene.py -- --out "$work/hdri.json" --hdri \
  >>"$work/blender.log" 2>&1 || { tail -20 "$work/blender.log"; echo "$check: unmappable_scene.py --hdri failed" >&2; exit 1; }
expect "world 'World': image 'generated sky' is generated: wrote its float EXR copy $work/generated_sky.exr"
expect "world 'World': Mapping's X, Y rotation 10, 0 deg, scale [2.0, 2.0, 2.0]: phongcl rotates an environment about Z only; left out"
python3 - "$work/hdri.json" <<'PY'
import json, os, sys
sys.path.insert(0, "scripts/blender")
import exr_file
scene = json.load(open(sys.argv[1]))
world = [light for light in scene["lights"] if light["type"] == "environment"]
assert world == [{"type": "environment", "file": "generated_sky.exr", "rotation": -30, "strength": 1, "shadows": True}], world
copy, size = exr_file.read(os.path.join(os.path.dirname(sys.argv[1]), world[0]["file"]), ["R", "G", "B"])
# unmappable_scene.HDRI_PIXELS, top row first: k = 4..7 above k = 0..3
assert size == (4, 2) and copy["R"] == [[2.0, 2.5, 3.0, 3.5], [0.0, 0.5, 1.0, 1.5]] and copy["B"] == [[2.0] * 4] * 2, copy
PY
echo "$check: $(grep -c '^export_scene: ' "$work/blender.log") notes, each unmappable feature named"
