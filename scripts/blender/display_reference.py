"""Blender's own 8-bit PNGs of a linear EXR, for holding phongcl's display transforms to them
(scripts/checks/63-blender-colour.sh, scripts/blender/make_colour_fixtures.sh):

    blender -b --factory-startup --python scripts/blender/display_reference.py -- \\
        --exr lit.exr --background 0.05,0.06,0.1 --cases tests/fixtures/colour/cases.txt --out DIR

Blender's compositor lays the EXR (premultiplied) over the background colour (Alpha Over on an RGB
node, as phongcl's previews are flattened), and each case of the cases file ("name | view | look |
exposure" per line, look "None" for none) is rendered with the scene's view settings on the sRGB
display, no dither, and written as DIR/<name>.png (8-bit RGB): the PNG Blender writes when it saves
that render.
"""
import argparse
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions  # noqa: E402


def read_cases(path):
    cases = []
    for line in open(path):
        line = line.split("#", 1)[0].strip()
        if line:
            name, view, look, exposure = (part.strip() for part in line.split("|"))
            cases.append((name, view, look, float(exposure)))
    return cases


def compositing_scene(exr, background):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    image = bpy.data.images.load(os.path.abspath(exr))
    scene.render.resolution_x, scene.render.resolution_y = image.size
    scene.render.resolution_percentage = 100
    scene.render.engine = "BLENDER_WORKBENCH"  # the render is unused: the compositor's output is saved
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    tree = blender_versions.compositor_tree(scene)
    tree.nodes.clear()
    plate = tree.nodes.new("CompositorNodeRGB")
    plate.outputs[0].default_value = (*background, 1.0)
    source = tree.nodes.new("CompositorNodeImage")
    source.image = image
    over = tree.nodes.new("CompositorNodeAlphaOver")
    under, above = blender_versions.alpha_over_inputs(over)
    tree.links.new(plate.outputs[0], under)
    tree.links.new(source.outputs["Image"], above)
    tree.links.new(over.outputs[0], blender_versions.composite_input(tree))
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.gamma = 1.0
    scene.render.dither_intensity = 0.0
    settings = scene.render.image_settings
    settings.file_format = "PNG"
    settings.color_mode = "RGB"
    settings.color_depth = "8"
    return scene


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exr", required=True)
    parser.add_argument("--background", required=True, help="r,g,b: the scene's background, linear")
    parser.add_argument("--cases", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    scene = compositing_scene(args.exr, [float(v) for v in args.background.split(",")])
    os.makedirs(args.out, exist_ok=True)
    for name, view, look, exposure in read_cases(args.cases):
        scene.view_settings.view_transform = view
        scene.view_settings.look = look
        scene.view_settings.exposure = exposure
        scene.render.filepath = os.path.join(os.path.abspath(args.out), name + ".png")
        bpy.ops.render.render(write_still=True)
        print(f"display_reference: {name}: {view}, look {look}, exposure {exposure:g}")


main()
