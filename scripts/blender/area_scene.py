"""The scene of the area light comparison (docs/shading.md "Area lights"): a ground plane under a
rectangle and a disk area light, pure diffuse (Lambert), no bounces, the light threshold at 0, and
Cycles' direct diffuse light of each light alone from pixel centres (box filter of 0.01 px). Cycles
samples an area light, so its light is noisy: --samples sets the samples per pixel. No smooth-shaded
objects: Cycles averages the Normal pass over a pixel's samples, so a 1024-sample render's normals
differ from the G-buffer's (4 samples) where normals vary within a pixel, which a sphere's do; the
emitters' planes meet the ground outside the frame, where their light falls to 0.

    blender -b --factory-startup --python scripts/blender/area_scene.py -- --out DIR [--width 96 --height 72] [--samples 1024] [--seed 1]

writes DIR/area.blend, with export_scene.py DIR/scene.json and DIR/gbuffer.exr, then DIR/light0.exr
(the rectangle) and DIR/light1.exr (the disk): each light alone, its DiffDir, DiffCol and IndexOB passes.
"""
import argparse
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402
import shadow_scene  # noqa: E402

# name, shape, location, rotation (XYZ Euler, radians), size, size_y, watts
LIGHTS = (("rect", "RECTANGLE", (2.0, -1.5, 3.0), (0.3, 0.2, 0.4), 2.0, 1.0, 300.0),
          ("disk", "DISK", (-2.6, -0.8, 2.2), (-0.08, -0.08, 0.0), 1.5, 1.5, 200.0))


def build_area_scene(width, height, samples):
    scene = make_fixtures.empty_scene(width, height, strength=0.0)  # no ambient light
    bpy.ops.mesh.primitive_plane_add(size=14.0, location=(0.0, 0.0, 0.0))
    ground = bpy.context.object
    ground.data.materials.append(shadow_scene.diffuse_material("ground", (0.6, 0.6, 0.55), 0))
    ground.pass_index = 1

    for name, shape, location, rotation, size, size_y, energy in LIGHTS:
        bpy.ops.object.light_add(type="AREA", location=location, rotation=rotation)
        light = bpy.context.object
        light.name = name
        light.data.shape = shape
        light.data.size, light.data.size_y = size, size_y
        light.data.energy = energy
        versions.set_casts_shadow(light.data, False)  # unshadowed light: phongcl's area shadows are hard, Cycles' soft

    make_fixtures.add_camera(scene, location=(6.5, -6.0, 3.6), target=(0.0, 0.0, 0.5), lens=40.0)
    bpy.context.view_layer.update()

    make_fixtures.cycles(scene, samples)
    scene.cycles.max_bounces = 0
    scene.cycles.light_sampling_threshold = 0.0
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "BOX", 0.01
    layer = bpy.context.view_layer
    layer.use_pass_diffuse_direct = True
    layer.use_pass_object_index = True
    return scene


def main():
    parser = argparse.ArgumentParser(prog="area_scene.py")
    parser.add_argument("--out", required=True)
    parser.add_argument("--width", type=int, default=96)
    parser.add_argument("--height", type=int, default=72)
    parser.add_argument("--samples", type=int, default=1024)
    parser.add_argument("--seed", type=int, default=1, help="Cycles' seed: two seeds measure the noise floor")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    scene = build_area_scene(args.width, args.height, args.samples)
    scene.cycles.seed = args.seed
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "area.blend"))
    export_scene.render_gbuffer(scene, os.path.join(out, "gbuffer.exr"), 4)
    export_scene.write_json(export_scene.scene_json(scene, "quadratic", "gbuffer.exr"), os.path.join(out, "scene.json"))
    shadow_scene.render_each_light(scene, out)


if __name__ == "__main__":
    main()
