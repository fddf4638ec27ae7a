"""Makes the Blender fixtures of tests/fixtures/blender/ (docs/formats.md "Renderers' G-buffers"):

    blender -b --factory-startup --python scripts/blender/make_fixtures.py -- --out tests/fixtures/blender
        [--width 64 --height 48] [--only cycles_depth.exr,...]

A sphere, a cube and a ground plane under a point light and a sun, sky above the horizon, rendered as
  cycles.exr       Cycles multilayer render (Position, Normal, Depth, IndexMA, DiffCol, GlossCol), opaque film
  cycles_depth.exr Cycles with Blender's default passes plus Normal, IndexMA, DiffCol, GlossCol: no Position
                   (positions are rebuilt from Depth), 4 samples
  file_output.exr  the same passes through a compositor File Output node (no view-layer prefix)
  eevee.exr        EEVEE: Depth, Normal, DiffCol, GlossCol (no position, no material pass)
  transparent.exr  Cycles with a transparent film and pass indices never set (all 0)
  supersampled.exr Cycles at 4x the size, box filter of 0.01 px, 1 sample: every sub-pixel one
                   centre sample, for measuring the edge policy
and scene.json (scripts/blender/export_scene.py) for the 1x frame.
"""
import argparse
import glob
import math
import os
import shutil
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402


def material(name, colour, roughness, pass_index):
    m = bpy.data.materials.new(name)
    bsdf = versions.use_nodes(m).nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    m.pass_index = pass_index
    return m


def empty_scene(width, height, sky=(0.05, 0.05, 0.06), strength=1.0):
    """A new empty scene of width x height pixels under a uniform sky."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = width, height, 100
    world = bpy.data.worlds.new("World")
    background = versions.use_nodes(world).nodes["Background"]
    background.inputs["Color"].default_value = (*sky, 1.0)
    background.inputs["Strength"].default_value = strength
    scene.world = world
    return scene


def build_scene(width, height):
    scene = empty_scene(width, height)

    bpy.ops.mesh.primitive_plane_add(size=30.0, location=(0.0, 0.0, 0.0))
    bpy.context.object.data.materials.append(material("ground", (0.5, 0.5, 0.45), 0.8, 0))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(0.0, 0.0, 1.0), segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(material("red", (0.8, 0.1, 0.1), 0.3, 1))
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(1.4, -1.6, 0.5), rotation=(0.0, 0.0, 0.6))
    bpy.context.object.data.materials.append(material("blue", (0.1, 0.2, 0.8), 0.5, 2))

    bpy.ops.object.light_add(type="POINT", location=(3.0, -2.0, 5.0))
    bpy.context.object.data.energy = 1000.0
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(50.0), 0.0, math.radians(30.0)))
    bpy.context.object.data.energy = 2.0

    bpy.ops.object.camera_add(location=(6.0, -6.0, 2.5))
    camera = bpy.context.object
    camera.data.lens = 40.0
    direction = Vector((0.0, 0.0, 0.8)) - camera.location
    camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera
    bpy.context.view_layer.update()  # matrix_world of the objects just placed

    cycles(scene, 16)
    return scene


def add_camera(scene, location, target, lens):
    """The scene's camera at `location`, looking at `target`, up along +Z."""
    bpy.ops.object.camera_add(location=location)
    camera = bpy.context.object
    camera.data.lens = lens
    camera.rotation_euler = (Vector(target) - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera


def cycles(scene, samples):
    """Cycles on the CPU, a fixed number of samples and seed, no denoising: renders that repeat."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = 1


def render(scene, path):
    export_scene.multilayer_exr(scene.render.image_settings)
    scene.render.use_file_extension = False
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def add_file_output(scene, directory):
    """A File Output node writing the render layer's passes as a multilayer EXR; returns its file pattern."""
    tree = versions.compositor_tree(scene)
    layers = versions.render_layers_node(tree)
    node = tree.nodes.new("CompositorNodeOutputFile")
    export_scene.multilayer_exr(node.format)
    versions.set_file_output_path(node, directory, "file_output_")
    names = ("Image", "Alpha", "Depth", "Normal", "Position", "IndexMA", "DiffCol", "GlossCol")
    versions.add_file_output_inputs(node, [(name, versions.render_layer_output(layers, name)) for name in names])
    for name in names:
        tree.links.new(versions.render_layer_output(layers, name), node.inputs[name])
    return os.path.join(directory, "file_output_*")  # 3.x/4.x add the frame number, 5.x the extension


def output_arguments(prog, width, height, only=False):
    """--out DIR (made if missing) and the image size, from the arguments after Blender's "--"; with
    only, also --only."""
    parser = argparse.ArgumentParser(prog=prog)
    parser.add_argument("--out", required=True)
    parser.add_argument("--width", type=int, default=width)
    parser.add_argument("--height", type=int, default=height)
    if only:
        parser.add_argument("--only", help="comma-separated fixture names to make (default: all); the others are left as they are")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    return args


def make_scene_json(scene, out):
    export_scene.enable_passes(bpy.context.view_layer)
    export_scene.write_json(export_scene.scene_json(scene), os.path.join(out, "scene.json"))


def make_cycles_and_file_output(scene, out):
    export_scene.enable_passes(bpy.context.view_layer)
    pattern = add_file_output(scene, out)
    render(scene, os.path.join(out, "cycles.exr"))
    written = glob.glob(pattern)
    shutil.move(written[0], os.path.join(out, "file_output.exr"))
    versions.disable_compositor(scene)


def make_supersampled(scene, out):
    export_scene.enable_passes(bpy.context.view_layer)
    scene.cycles.pixel_filter_type, scene.cycles.filter_width, scene.cycles.samples = "BOX", 0.01, 1
    scene.render.resolution_percentage = 400
    bpy.context.view_layer.use_pass_glossy_color = False  # not needed there; keeps the file small
    render(scene, os.path.join(out, "supersampled.exr"))
    bpy.context.view_layer.use_pass_glossy_color = True
    scene.cycles.pixel_filter_type, scene.cycles.filter_width, scene.cycles.samples = "BLACKMAN_HARRIS", 1.5, 16
    scene.render.resolution_percentage = 100


def make_transparent(scene, out):
    export_scene.enable_passes(bpy.context.view_layer)
    pass_indices = [m.pass_index for m in bpy.data.materials]
    scene.render.film_transparent = True
    for m in bpy.data.materials:
        m.pass_index = 0
    render(scene, os.path.join(out, "transparent.exr"))
    scene.render.film_transparent = False
    for m, index in zip(bpy.data.materials, pass_indices):
        m.pass_index = index


def make_cycles_depth(scene, out):
    """Position is off by default in Blender: positions come from Depth and the camera."""
    export_scene.enable_passes(bpy.context.view_layer, position=False)
    bpy.context.view_layer.use_pass_position = False
    samples = scene.cycles.samples
    scene.cycles.samples = 4
    render(scene, os.path.join(out, "cycles_depth.exr"))
    scene.cycles.samples = samples


def make_eevee(scene, out):
    scene.render.engine = versions.EEVEE_ENGINE
    scene.eevee.taa_render_samples = 16
    view_layer = bpy.context.view_layer
    view_layer.use_pass_position = False
    view_layer.use_pass_material_index = False
    render(scene, os.path.join(out, "eevee.exr"))
    scene.render.engine = "CYCLES"


# In the order `main` makes them all (EEVEE last: it changes the engine).
MAKERS = {
    "scene.json": make_scene_json,
    "cycles.exr": make_cycles_and_file_output,  # and file_output.exr
    "supersampled.exr": make_supersampled,
    "transparent.exr": make_transparent,
    "cycles_depth.exr": make_cycles_depth,
    "eevee.exr": make_eevee,
}


def main():
    args = output_arguments("make_fixtures.py", 64, 48, only=True)
    out = args.out

    scene = build_scene(args.width, args.height)
    if args.only:
        for name in args.only.split(","):
            MAKERS[name](scene, out)
        return
    for make in MAKERS.values():
        make(scene, out)


if __name__ == "__main__":
    main()
