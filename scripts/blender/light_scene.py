"""The scene of the light-type comparison with Cycles (docs/formats.md "Lights from Blender"): spheres
on a ground plane under two spot lights (one with a blend), a point light and a sun, pure diffuse
(Lambert), no bounces, no shadows, and Cycles' direct diffuse light of each light alone, rendered from
pixel centres (box filter of 0.01 px, one sample: a light of radius 0 alone, no bounces, gives the
exact direct light at each pixel centre, noiseless). Each light is in a light group of its own but
the sun, which is in none, so each render's light group pass is that light's Combined light.

    blender -b --factory-startup --python scripts/blender/light_scene.py -- --out DIR [--width 96 --height 72]

writes DIR/lights.blend, with export_scene.py DIR/scene.json and DIR/gbuffer.exr, then DIR/light<k>.exr
for each light k of scene.json's order: its DiffDir (direct diffuse light), DiffCol (albedo), IndexOB
(object index, for finding silhouettes), Depth and light group passes (Combined_<group>).
"""
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402
import shadow_scene  # noqa: E402

# name, type, location, target, watts (W/m^2 for the sun), spot size (degrees), blend, light group
LIGHTS = (("key", "SPOT", (3.0, -3.0, 5.0), (0.3, 0.2, 0.0), 1500.0, 55.0, 0.3, "keys"),
          ("rim", "SPOT", (-4.0, 2.5, 4.0), (-0.5, 0.0, 0.5), 1200.0, 45.0, 0.0, "rims"),
          ("fill", "POINT", (-3.0, -4.0, 3.0), None, 400.0, 0.0, 0.0, "fills"),
          ("sky", "SUN", (0.0, 0.0, 10.0), (1.0, 2.0, 0.0), 1.5, 0.0, 0.0, ""))


def build_light_scene(width, height):
    scene = make_fixtures.empty_scene(width, height, strength=0.0)  # no ambient light

    objects = []
    bpy.ops.mesh.primitive_plane_add(size=14.0, location=(0.0, 0.0, 0.0))
    objects.append((bpy.context.object, shadow_scene.diffuse_material("ground", (0.6, 0.6, 0.55), 0)))
    red = shadow_scene.diffuse_material("red", (0.8, 0.15, 0.1), 1)
    blue = shadow_scene.diffuse_material("blue", (0.15, 0.25, 0.8), 2)
    for radius, location, material in ((1.0, (0.0, 0.0, 1.0), red), (0.6, (-1.9, 0.9, 0.6), blue)):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=64, ring_count=32)
        bpy.ops.object.shade_smooth()
        objects.append((bpy.context.object, material))
    for index, (obj, material) in enumerate(objects, start=1):
        obj.data.materials.append(material)
        obj.pass_index = index

    layer = bpy.context.view_layer
    for name, kind, location, target, power, size, blend, group in LIGHTS:
        bpy.ops.object.light_add(type=kind, location=location)
        light = bpy.context.object
        light.name = name
        light.data.energy = power
        versions.set_casts_shadow(light.data, False)
        if kind != "SUN":
            light.data.shadow_soft_size = 0.0  # a point: exact at one sample
        else:
            light.data.angle = 0.0
        if target is not None:
            light.rotation_euler = (Vector(target) - light.location).to_track_quat("-Z", "Y").to_euler()
        if kind == "SPOT":
            light.data.spot_size = size * 3.14159265358979 / 180.0
            light.data.spot_blend = blend
        if group:
            if group not in layer.lightgroups:
                layer.lightgroups.add(name=group)
            light.lightgroup = group

    make_fixtures.add_camera(scene, location=(6.5, -6.0, 3.6), target=(0.0, 0.0, 0.5), lens=40.0)
    layer.update()

    make_fixtures.cycles(scene, 1)
    scene.cycles.max_bounces = 0
    scene.cycles.light_sampling_threshold = 0.0
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "BOX", 0.01
    layer.use_pass_diffuse_direct = True
    layer.use_pass_object_index = True
    return scene


def main():
    args = make_fixtures.output_arguments("light_scene.py", 96, 72)
    out = args.out
    scene = build_light_scene(args.width, args.height)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "lights.blend"))
    export_scene.render_gbuffer(scene, os.path.join(out, "gbuffer.exr"))
    document = export_scene.scene_json(scene, "quadratic", "gbuffer.exr")
    export_scene.write_json(document, os.path.join(out, "scene.json"))
    shadow_scene.render_each_light(scene, out)


if __name__ == "__main__":
    main()
