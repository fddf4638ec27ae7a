"""The scene of the Principled comparison (docs/shading.md "Principled"): Principled BSDF spheres
(roughness 0.15 to 0.6, a metal, specular 0.5 and 1.0, a tinted specular; on 4.3+ the floor's and the
roughest sphere's Diffuse Roughness 0.5 and 1) on a Principled floor, under a
point, a spot and a sun light without size and shadows, no bounces, the light threshold at 0, each light rendered alone from pixel centres
(box filter of 0.01 px: with one light of no size and no bounces the direct light at a pixel centre is
exact; --seed changes Cycles' seed, so that two renders measure its noise). With --area the lights are
a rect and a disk area light instead (no shadows), which Cycles samples: --samples per pixel.

    blender -b --factory-startup --python scripts/blender/principled_scene.py -- --out DIR [--width 160 --height 120] [--seed 0]
        [--area --samples 256]

writes DIR/scene.json and DIR/gbuffer.exr (export_scene.py), then DIR/light0.exr ... each light alone:
its DiffDir, DiffCol, GlossDir, GlossCol, IndexOB and Depth passes.
"""
import argparse
import math
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402
import shadow_scene  # noqa: E402

# name, base colour, metallic, roughness, specular (3.x; 4.0+: Specular IOR Level), specular tint, place
SPHERES = (("rough15", (0.8, 0.2, 0.1), 0.0, 0.15, 0.5, 0.0, (-2.4, 0.0, 0.7)),
           ("rough30", (0.2, 0.5, 0.8), 0.0, 0.3, 1.0, 0.0, (-0.8, 0.0, 0.7)),
           ("rough60", (0.3, 0.7, 0.3), 0.0, 0.6, 0.5, 0.5, (0.8, 0.0, 0.7)),
           ("metal", (0.95, 0.7, 0.35), 1.0, 0.3, 0.5, 0.0, (2.4, 0.0, 0.7)))
FLOOR = ("floor", (0.5, 0.5, 0.5), 0.0, 0.4, 0.5, 0.0)
# 4.3 on: Diffuse Roughness (Cycles' Oren-Nayar) on the floor and the roughest sphere
DIFFUSE_ROUGHNESS = {"floor": 0.5, "rough60": 1.0} if versions.IMPROVED_OREN_NAYAR else {}
# name, type, location, watts (W/m^2 for the sun)
LIGHTS = (("point", "POINT", (2.0, -3.0, 4.0), 800.0), ("spot", "SPOT", (-3.0, -2.5, 3.5), 900.0),
          ("sun", "SUN", (0.0, 3.0, 5.0), 3.0))
# --area: name, shape, location, size, size_y, watts; each aimed at the spheres' middle
AREA_LIGHTS = (("rect", "RECTANGLE", (1.5, -2.5, 3.5), 1.5, 0.8, 400.0),
               ("disk", "DISK", (-2.0, -1.5, 3.0), 1.2, 1.2, 300.0))


def principled_material(name, colour, metallic, roughness, specular, tint, pass_index):
    m = bpy.data.materials.new(name)
    node = versions.use_nodes(m).nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    if versions.at_least(4):
        node.inputs["Specular IOR Level"].default_value = specular
        if name in DIFFUSE_ROUGHNESS:
            node.inputs["Diffuse Roughness"].default_value = DIFFUSE_ROUGHNESS[name]
    else:
        node.inputs["Specular"].default_value = specular
        node.inputs["Specular Tint"].default_value = tint
    m.pass_index = pass_index
    return m


def add_lights():
    for name, kind, location, energy in LIGHTS:
        bpy.ops.object.light_add(type=kind, location=location)
        light = bpy.context.object
        light.name = name
        light.data.energy = energy
        versions.set_casts_shadow(light.data, False)  # the comparison is of the BSDF, not of shadows
        light.rotation_euler = (Vector((0.0, 0.0, 0.5)) - Vector(location)).to_track_quat("-Z", "Y").to_euler()
        if kind == "SUN":
            light.data.angle = 0.0
        else:
            light.data.shadow_soft_size = 0.0
        if kind == "SPOT":
            light.data.spot_size, light.data.spot_blend = math.radians(80.0), 0.2


def add_area_lights():
    for name, shape, location, size, size_y, energy in AREA_LIGHTS:
        bpy.ops.object.light_add(type="AREA", location=location)
        light = bpy.context.object
        light.name = name
        light.data.shape = shape
        light.data.size, light.data.size_y = size, size_y
        light.data.energy = energy
        versions.set_casts_shadow(light.data, False)
        light.rotation_euler = (Vector((0.0, 0.0, 0.5)) - Vector(location)).to_track_quat("-Z", "Y").to_euler()


def build_scene(width, height, seed, area=False, samples=1):
    scene = make_fixtures.empty_scene(width, height, strength=0.0)
    bpy.ops.mesh.primitive_plane_add(size=14.0, location=(0.0, 0.0, 0.0))
    objects = [(bpy.context.object, principled_material(*FLOOR, 0))]
    for index, (name, colour, metallic, roughness, specular, tint, place) in enumerate(SPHERES, start=1):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, location=place, segments=96, ring_count=48)
        bpy.ops.object.shade_smooth()
        objects.append((bpy.context.object, principled_material(name, colour, metallic, roughness, specular, tint, index)))
    for index, (obj, material) in enumerate(objects, start=1):
        obj.data.materials.append(material)
        obj.pass_index = index
    if area:
        add_area_lights()
    else:
        add_lights()
    make_fixtures.add_camera(scene, location=(0.0, -7.5, 3.2), target=(0.0, 0.0, 0.6), lens=40.0)
    bpy.context.view_layer.update()
    make_fixtures.cycles(scene, samples if area else 1)
    scene.cycles.seed = seed
    scene.cycles.max_bounces = 0
    # Below the threshold Cycles plays Russian roulette with a light's sample: 0 or 0.01, not the light.
    scene.cycles.light_sampling_threshold = 0.0
    # Pixel centres, as phongcl shades them: a Gaussian of 0.01 px (Cycles widens a box to one pixel).
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "GAUSSIAN", 0.01
    layer = bpy.context.view_layer
    layer.use_pass_diffuse_direct = True
    layer.use_pass_glossy_direct = True
    layer.use_pass_object_index = True
    return scene


def main():
    parser = argparse.ArgumentParser(prog="principled_scene.py")
    parser.add_argument("--out", required=True)
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=120)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--area", action="store_true", help="a rect and a disk area light instead")
    parser.add_argument("--samples", type=int, default=256, help="--area: samples per pixel")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    scene = build_scene(args.width, args.height, args.seed, args.area, args.samples)
    # One sample: the filter is a point, so the passes are the pixel centre's whatever the count; the
    # area lights' samples are for the light renders.
    export_scene.render_gbuffer(scene, os.path.join(out, "gbuffer.exr"), samples=1)
    document = export_scene.scene_json(scene, "quadratic", "gbuffer.exr", None)
    export_scene.write_json(document, os.path.join(out, "scene.json"))
    shadow_scene.render_each_light(scene, out)


if __name__ == "__main__":
    main()
