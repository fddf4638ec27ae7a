"""The scene of the shadow comparison (docs/shadows.md): spheres and a box on a ground plane under two
point lights that cast hard shadows, pure diffuse (Lambert), no bounces, and Cycles' direct diffuse
light of each light alone, rendered from pixel centres (a Gaussian filter of 0.01 px, one sample: with
one point light of radius 0 and no bounces, the direct light at a pixel centre is exact, noiseless).
With --soft the lights have a size and cast soft shadows: a 2 m square area light, a point and a spot
light of radius 0.25 m and a sun of 10 degrees, each rendered with --samples samples per pixel (the
penumbra's light is then an estimate whose noise the comparison's tolerance must hold). With
--unshadowed each light is rendered a second time with its shadows off, DIR/light0-unshadowed.exr, ...:
the renderer's own unshadowed light, the base of the comparison's tolerance.

    blender -b --factory-startup --python scripts/blender/shadow_scene.py -- --out DIR [--width 320 --height 240] [--soft --samples 512]

writes DIR/shadows.blend, and with export_scene.py (--geometry) DIR/scene.json, DIR/gbuffer.exr and
DIR/meshes/*.ply, then DIR/light0.exr, DIR/light1.exr: each light alone, its DiffDir (direct diffuse
light), DiffCol (albedo) and IndexOB (object index, for finding silhouettes) passes.
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

LIGHTS = (("key", (3.0, -2.0, 5.0), 1000.0), ("fill", (-3.5, -1.0, 3.0), 600.0))
# --soft: name, type, location, watts (W/m^2 for the sun), size (area: metres; point, spot: radius;
# sun: angle in degrees)
SOFT_LIGHTS = (("panel", "AREA", (0.5, -0.5, 4.0), 600.0, 2.0), ("bulb", "POINT", (3.0, -2.0, 5.0), 1000.0, 0.25),
               ("cone", "SPOT", (-3.5, -1.0, 3.0), 800.0, 0.25), ("sun", "SUN", (0.0, 0.0, 6.0), 3.0, 10.0))


def diffuse_material(name, colour, pass_index):
    """Lambert: a Diffuse BSDF of roughness 0 (the exporter reads kd from diffuse_color)."""
    m = bpy.data.materials.new(name)
    m.diffuse_color = (*colour, 1.0)
    nodes = versions.use_nodes(m).nodes
    nodes.remove(nodes["Principled BSDF"])
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    m.node_tree.links.new(bsdf.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    m.pass_index = pass_index
    m.specular_intensity = 0.0
    return m


def add_point_lights():
    for name, location, energy in LIGHTS:
        bpy.ops.object.light_add(type="POINT", location=location)
        light = bpy.context.object
        light.name = name
        light.data.energy = energy
        light.data.shadow_soft_size = 0.0  # a point: hard shadows


def add_soft_lights():
    for name, kind, location, energy, size in SOFT_LIGHTS:
        bpy.ops.object.light_add(type=kind, location=location)
        light = bpy.context.object
        light.name = name
        light.data.energy = energy
        # Aimed at the scene's middle: the lights' -Z towards (0, 0, 0.5).
        light.rotation_euler = (Vector((0.0, 0.0, 0.5)) - Vector(location)).to_track_quat("-Z", "Y").to_euler()
        if kind == "AREA":
            light.data.size = size
        elif kind == "SUN":
            light.data.angle = math.radians(size)
        else:
            light.data.shadow_soft_size = size
        if kind == "SPOT":
            light.data.spot_size, light.data.spot_blend = math.radians(90.0), 0.2


def build_shadow_scene(width, height, add_lights=add_point_lights, samples=1):
    scene = make_fixtures.empty_scene(width, height, strength=0.0)  # no ambient light

    objects = []
    bpy.ops.mesh.primitive_plane_add(size=14.0, location=(0.0, 0.0, 0.0))
    objects.append((bpy.context.object, diffuse_material("ground", (0.6, 0.6, 0.55), 0)))
    red = diffuse_material("red", (0.8, 0.15, 0.1), 1)
    blue = diffuse_material("blue", (0.15, 0.25, 0.8), 2)
    for radius, location, material in ((1.0, (0.0, 0.0, 1.0), red), (0.6, (-1.9, 0.9, 0.6), blue),
                                       (0.45, (1.6, -1.0, 0.45), blue)):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=64, ring_count=32)
        bpy.ops.object.shade_smooth()
        objects.append((bpy.context.object, material))
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(1.3, 1.4, 0.4), rotation=(0.0, 0.0, 0.5))
    objects.append((bpy.context.object, red))
    for index, (obj, material) in enumerate(objects, start=1):
        obj.data.materials.append(material)
        obj.pass_index = index

    add_lights()

    make_fixtures.add_camera(scene, location=(6.5, -6.0, 3.6), target=(0.0, 0.0, 0.5), lens=40.0)
    bpy.context.view_layer.update()

    make_fixtures.cycles(scene, samples)
    scene.cycles.max_bounces = 0
    # Pixel centres: Cycles widens a box filter to one pixel whatever its width (BlenderSync::sync_film),
    # which averaged each pixel over its area (a cone's edge, a penumbra, a terminator blurred by the
    # pixel, against phongcl's centre); a Gaussian keeps its width, 0.01 px the smallest Blender takes.
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "GAUSSIAN", 0.01
    layer = bpy.context.view_layer
    layer.use_pass_diffuse_direct = True
    layer.use_pass_object_index = True
    return scene


def render_each_light(scene, directory, suffix=""):
    lights = [o for o in scene.objects if o.type == "LIGHT"]
    for k, light in enumerate(lights):
        for other in lights:
            other.hide_render = other is not light
        export_scene.enable_passes(bpy.context.view_layer)
        export_scene.multilayer_exr(scene.render.image_settings)
        scene.render.use_file_extension = False
        scene.render.filepath = os.path.join(directory, "light%d%s.exr" % (k, suffix))
        bpy.ops.render.render(write_still=True)
    for light in lights:
        light.hide_render = False


def render_each_light_unshadowed(scene, directory):
    """Each light alone with its shadows off (after the export, which writes the lights' shadows on)."""
    lights = [o for o in scene.objects if o.type == "LIGHT"]
    for light in lights:
        versions.set_casts_shadow(light.data, False)
    render_each_light(scene, directory, "-unshadowed")
    for light in lights:
        versions.set_casts_shadow(light.data, True)


def main():
    parser = argparse.ArgumentParser(prog="shadow_scene.py")
    parser.add_argument("--out", required=True)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--soft", action="store_true", help="lights with a size, casting soft shadows")
    parser.add_argument("--samples", type=int, default=512, help="--soft: samples per pixel")
    parser.add_argument("--unshadowed", action="store_true",
                        help="also render each light with its shadows off (lightK-unshadowed.exr)")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    if args.soft:
        scene = build_shadow_scene(args.width, args.height, add_soft_lights, args.samples)
    else:
        scene = build_shadow_scene(args.width, args.height)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "shadows.blend"))
    export_scene.render_gbuffer(scene, os.path.join(out, "gbuffer.exr"), samples=1)  # the centre: the filter is a point
    objects = export_scene.export_geometry(scene, os.path.join(out, "meshes"), out)
    document = export_scene.scene_json(scene, "quadratic", "gbuffer.exr", objects)
    export_scene.write_json(document, os.path.join(out, "scene.json"))
    render_each_light(scene, out)
    if args.unshadowed:
        render_each_light_unshadowed(scene, out)


if __name__ == "__main__":
    main()
