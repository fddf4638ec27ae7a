"""A scene holding what export_scene.py cannot map, for scripts/checks/61-blender-notes.sh: a world lit by
a Sky Texture, an ellipse area light, a Principled BSDF that emits, transmits and whose Base Color
is fed by a texture, a Glass BSDF, and a spot light of a non-zero radius (exported as its "radius"). Writes the scene JSON;
the exporter's notes go to standard output. No render. With --hdri the world is instead a generated 4x2 float image
(HDRI_PIXELS, which no file holds: the exporter writes its EXR copy) through a Mapping of type Texture turned by
30 degrees about Z (exported as -30), 10 about X and scaled by 2 (each left out with a note).

    blender -b --factory-startup --python scripts/blender/unmappable_scene.py -- --out scene.json [--hdri]
"""
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402


HDRI_PIXELS = [(0.5 * k, 0.25 * k, 2.0, 1.0) for k in range(8)]  # bottom row first, as Blender's pixels


def generated_hdri_world(world):
    image = bpy.data.images.new("generated sky", 4, 2, alpha=True, float_buffer=True)
    image.pixels.foreach_set([c for pixel in HDRI_PIXELS for c in pixel])
    texture = world.nodes.new("ShaderNodeTexEnvironment")
    texture.image = image
    mapping = world.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "TEXTURE"
    mapping.inputs["Rotation"].default_value = (math.radians(10.0), 0.0, math.radians(30.0))
    mapping.inputs["Scale"].default_value = (2.0, 2.0, 2.0)
    world.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    world.links.new(texture.outputs["Color"], world.nodes["Background"].inputs["Color"])


def build_unmappable_scene(hdri):
    scene = make_fixtures.build_scene(32, 24)
    world = versions.node_tree(scene.world)
    if hdri:
        generated_hdri_world(world)
    else:
        sky = world.nodes.new("ShaderNodeTexSky")
        world.links.new(sky.outputs["Color"], world.nodes["Background"].inputs["Color"])

    for name, kind, shape in (("oval", "AREA", "ELLIPSE"), ("panel", "AREA", "RECTANGLE"), ("cone", "SPOT", None)):
        bpy.ops.object.light_add(type=kind, location=(0.0, 1.0, 3.0))
        light = bpy.context.object
        light.name = name
        if shape:
            light.data.shape = shape
        if kind == "SPOT":
            light.data.shadow_soft_size = 0.25
            versions.set_casts_shadow(light.data, False)

    red = versions.node_tree(bpy.data.materials["red"])
    principled = red.nodes["Principled BSDF"]
    principled.inputs[versions.PRINCIPLED_EMISSION].default_value = (1.0, 1.0, 1.0, 1.0)
    principled.inputs["Emission Strength"].default_value = 2.0
    # Transmission, which neither version of phongcl's principled material has (4.0 renamed the socket).
    principled.inputs["Transmission Weight" if versions.at_least(4) else "Transmission"].default_value = 0.5
    noise = red.nodes.new("ShaderNodeTexNoise")
    red.links.new(noise.outputs["Color"], principled.inputs["Base Color"])

    blue = versions.node_tree(bpy.data.materials["blue"])
    glass = blue.nodes.new("ShaderNodeBsdfGlass")
    blue.links.new(glass.outputs["BSDF"], blue.nodes["Material Output"].inputs["Surface"])
    return scene


def main():
    arguments = sys.argv[sys.argv.index("--") + 1:]
    out = os.path.abspath(arguments[1])
    scene = build_unmappable_scene("--hdri" in arguments)
    export_scene.write_json(export_scene.scene_json(scene, "quadratic", directory=os.path.dirname(out)), out)


if __name__ == "__main__":
    main()
