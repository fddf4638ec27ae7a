"""The scene of the relight-over-the-render check (docs/compositing.md): spheres and a box on a floor,
Principled materials, shadows, two bounces and a dim grey world, lit by a key point light, a fill area
light and a rim spot, each in a light group of its own, rendered by Cycles with every light group's
Combined pass; then Cycles' renders of two edits, for phongcl's composite to be held to:

    blender -b --factory-startup --python scripts/blender/over_scene.py -- --out DIR [--width 160 --height 120]

(PHONGCL_OVER_SAMPLES sets Cycles' samples, default 1024: at 256, Cycles' noise alone leaves 1.8% of
the pixels of two seeds' renders more than 5% apart on Blender 4.x and 5.x, and a moved light's render
draws other paths, so a composite cannot agree with it on much more than 96%)

writes DIR/over.blend, with export_scene.py DIR/scene.json (its "rendered" lights, its meshes in DIR/meshes
for shadows) and DIR/render.exr (the G-buffer, Combined and Combined_<group> passes, object index), then
  DIR/brighter0.exr, DIR/brighter1.exr: the key light at twice its power, seeds 0 and 1 (Cycles' noise);
  DIR/moved.exr: the key light moved by MOVE (0.5 m), seed 0 as the render's.
"""
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402

MOVE = Vector((0.5, 0.0, 0.0))
# name, type, location, target, watts, light group
LIGHTS = (("key", "POINT", (3.0, -3.0, 4.5), None, 900.0, "key"),
          ("fill", "AREA", (-4.0, -2.0, 3.0), (0.0, 0.0, 0.5), 500.0, "fill"),
          ("rim", "SPOT", (-1.0, 4.5, 4.0), (0.0, 0.0, 0.5), 800.0, "rim"))


def build_over_scene(width, height, samples):
    scene = make_fixtures.empty_scene(width, height, sky=(0.05, 0.05, 0.05), strength=1.0)
    bpy.ops.mesh.primitive_plane_add(size=14.0, location=(0.0, 0.0, 0.0))
    objects = [(bpy.context.object, make_fixtures.material("floor", (0.6, 0.6, 0.55), 0.6, 0))]
    for radius, location, colour, roughness in ((1.0, (0.0, 0.0, 1.0), (0.8, 0.15, 0.1), 0.3),
                                                (0.6, (-1.9, 0.9, 0.6), (0.15, 0.25, 0.8), 0.5)):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=64, ring_count=32)
        bpy.ops.object.shade_smooth()
        objects.append((bpy.context.object, make_fixtures.material("ball%d" % len(objects), colour, roughness, len(objects))))
    bpy.ops.mesh.primitive_cube_add(size=0.9, location=(1.6, 1.2, 0.45))
    objects.append((bpy.context.object, make_fixtures.material("box", (0.3, 0.6, 0.3), 0.45, len(objects))))
    for index, (obj, material) in enumerate(objects, start=1):
        obj.data.materials.append(material)
        obj.pass_index = index

    layer = bpy.context.view_layer
    for name, kind, location, target, power, group in LIGHTS:
        bpy.ops.object.light_add(type=kind, location=location)
        light = bpy.context.object
        light.name = name
        light.data.energy = power
        versions.set_casts_shadow(light.data, True)
        if kind == "AREA":
            light.data.size = 1.0
        else:
            light.data.shadow_soft_size = 0.0
        if target is not None:
            light.rotation_euler = (Vector(target) - light.location).to_track_quat("-Z", "Y").to_euler()
        if kind == "SPOT":
            light.data.spot_size = 0.9
            light.data.spot_blend = 0.2
        if group not in layer.lightgroups:
            layer.lightgroups.add(name=group)
        light.lightgroup = group

    make_fixtures.add_camera(scene, location=(6.5, -6.0, 3.6), target=(0.0, 0.0, 0.5), lens=40.0)
    layer.update()
    make_fixtures.cycles(scene, samples)
    scene.cycles.max_bounces = 2
    layer.use_pass_object_index = True
    return scene


def render_edit(scene, path, seed):
    scene.cycles.seed = seed
    make_fixtures.render(scene, path)


def main():
    args = make_fixtures.output_arguments("over_scene.py", 160, 120)
    samples = int(os.environ.get("PHONGCL_OVER_SAMPLES", "1024"))
    out = args.out
    scene = build_over_scene(args.width, args.height, samples)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "over.blend"))
    scene.cycles.seed = 0
    export_scene.render_gbuffer(scene, os.path.join(out, "render.exr"))
    objects = export_scene.export_geometry(scene, os.path.join(out, "meshes"), out)  # shadows traced as Cycles traced them
    export_scene.write_json(export_scene.scene_json(scene, "quadratic", "render.exr", objects), os.path.join(out, "scene.json"))
    key = scene.objects["key"]
    key.data.energy *= 2.0
    for seed in (0, 1):
        render_edit(scene, os.path.join(out, "brighter%d.exr" % seed), seed)
    key.data.energy /= 2.0
    key.location += MOVE
    render_edit(scene, os.path.join(out, "moved.exr"), 0)


if __name__ == "__main__":
    main()
