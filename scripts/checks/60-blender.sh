#!/usr/bin/env bash
# A .blend to a relit EXR with the two commands of the README's "Shade your own render": builds a
# tiny scene in Blender (64x48: point, spot, sun, rect and disk area lights and the world, all casting shadows;
# Principled and Diffuse materials), exports it and renders its G-buffer with Cycles (4 samples, CPU) through
# scripts/blender/export_scene.py, then shades it with phongcl, which must detect the Blender
# layout with no flags beyond --scene. Needs build/phongcl (scripts/test.sh builds it first).
# BLENDER=PATH runs it with another Blender (scripts/setup.sh blender4, blender5).
set -euo pipefail
cd "$(dirname "$0")/../.."
check=60-blender
source scripts/checks/lib/blender_check.sh

"$blender" -b --factory-startup --python-exit-code 1 --python-expr "
import sys; sys.path.insert(0, 'scripts/blender')
import bpy, blender_versions, make_fixtures, shadow_scene
make_fixtures.build_scene(64, 48)
# Every light type, each casting shadows, and a Diffuse BSDF beside the Principled ones.
for kind, shape, location in (('SPOT', None, (-3, -2, 4)), ('AREA', 'RECTANGLE', (2, 2, 3)), ('AREA', 'DISK', (-2, 2, 3))):
    bpy.ops.object.light_add(type=kind, location=location)
    light = bpy.context.object
    light.data.energy = 300.0
    if kind == 'SPOT':
        light.data.shadow_soft_size = 0.0
    light.rotation_euler = (-light.location).to_track_quat('-Z', 'Y').to_euler()
    if shape:
        light.data.shape = shape
for light in (o for o in bpy.context.scene.objects if o.type == 'LIGHT'):
    blender_versions.set_casts_shadow(light.data, True)
bpy.ops.mesh.primitive_cube_add(size=0.8, location=(-1.5, 1.0, 0.4))
bpy.context.object.data.materials.append(shadow_scene.diffuse_material('matte', (0.2, 0.6, 0.2), 3))
bpy.ops.wm.save_as_mainfile(filepath='$work/tiny.blend')
" >"$work/blender.log" 2>&1 || { tail -20 "$work/blender.log"; echo "60-blender: building the .blend failed" >&2; exit 1; }

"$blender" -b "$work/tiny.blend" --python-exit-code 1 --python scripts/blender/export_scene.py -- \
  --out "$work/scene.json" --render "$work/gbuffer.exr" --samples 4 >>"$work/blender.log" 2>&1 ||
  { tail -20 "$work/blender.log"; echo "60-blender: export_scene.py failed" >&2; exit 1; }

python3 - "$work/scene.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
kinds = sorted({light["type"] + ("-" + light["shape"] if "shape" in light else "") for light in scene["lights"]})
assert kinds == ["area-disk", "area-rect", "directional", "environment", "point", "spot"], kinds
assert all(light.get("shadows") for light in scene["lights"]), "a light lost its shadows"
specular = [m.get("specular_model") == "principled" or any(m.get("ks", [])) for m in scene["materials"]]
assert specular == [True, True, True, False], "Principled materials need a specular lobe, the Diffuse one none: %s" % specular
PY
"$phongcl" shade --scene "$work/scene.json" --out "$work/lit.exr" --png "$work/lit.png" >"$work/shade.log"
grep -q "layout     blender (view layer 'ViewLayer': Position, Normal" "$work/shade.log" ||
  { cat "$work/shade.log"; echo "60-blender: the Blender layout was not detected" >&2; exit 1; }
[ -s "$work/lit.exr" ] || { echo "60-blender: no output image" >&2; exit 1; }
echo "60-blender: exported, rendered (Cycles 64x48, 4 samples) and shaded: $(grep -o '[0-9,]* shaded' "$work/shade.log")"
