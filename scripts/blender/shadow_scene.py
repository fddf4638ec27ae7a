"""The scene of the shadow comparison (docs/shadows.md): spheres and a box on a ground plane under two
point lights that cast hard shadows, pure diffuse (Lambert), no bounces, and Cycles' direct diffuse
light of each light alone, rendered from pixel centres (box filter of 0.01 px, one sample: with one
point light of radius 0 and no bounces, the direct light at a pixel centre is exact, noiseless).

    blender -b --factory-startup --python scripts/blender/shadow_scene.py -- --out DIR [--width 320 --height 240]

writes DIR/shadows.blend, and with export_scene.py (--geometry) DIR/scene.json, DIR/gbuffer.exr and
DIR/meshes/*.ply, then DIR/light0.exr, DIR/light1.exr: each light alone, its DiffDir (direct diffuse
light), DiffCol (albedo) and IndexOB (object index, for finding silhouettes) passes.
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402

LIGHTS = (("key", (3.0, -2.0, 5.0), 1000.0), ("fill", (-3.5, -1.0, 3.0), 600.0))


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


def build_shadow_scene(width, height):
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

    for name, location, energy in LIGHTS:
        bpy.ops.object.light_add(type="POINT", location=location)
        light = bpy.context.object
        light.name = name
        light.data.energy = energy
        light.data.shadow_soft_size = 0.0  # a point: hard shadows

    make_fixtures.add_camera(scene, location=(6.5, -6.0, 3.6), target=(0.0, 0.0, 0.5), lens=40.0)
    bpy.context.view_layer.update()

    make_fixtures.cycles(scene, 1)
    scene.cycles.max_bounces = 0
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "BOX", 0.01
    layer = bpy.context.view_layer
    layer.use_pass_diffuse_direct = True
    layer.use_pass_object_index = True
    return scene


def render_each_light(scene, directory):
    lights = [o for o in scene.objects if o.type == "LIGHT"]
    for k, light in enumerate(lights):
        for other in lights:
            other.hide_render = other is not light
        export_scene.enable_passes(bpy.context.view_layer)
        export_scene.multilayer_exr(scene.render.image_settings)
        scene.render.use_file_extension = False
        scene.render.filepath = os.path.join(directory, "light%d.exr" % k)
        bpy.ops.render.render(write_still=True)
    for light in lights:
        light.hide_render = False


def main():
    args = make_fixtures.output_arguments("shadow_scene.py", 320, 240)
    out = args.out
    scene = build_shadow_scene(args.width, args.height)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "shadows.blend"))
    export_scene.render_gbuffer(scene, os.path.join(out, "gbuffer.exr"))
    objects = export_scene.export_geometry(scene, os.path.join(out, "meshes"), out)
    document = export_scene.scene_json(scene, "quadratic", "gbuffer.exr", objects)
    export_scene.write_json(document, os.path.join(out, "scene.json"))
    render_each_light(scene, out)


if __name__ == "__main__":
    main()
