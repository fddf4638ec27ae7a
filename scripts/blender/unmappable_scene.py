"""A scene holding what export_scene.py cannot map, for scripts/checks/61-blender-notes.sh: a world lit by
a Sky Texture, an ellipse area light, a Principled BSDF that emits and whose Base Color
is fed by a texture, a Glass BSDF, and a spot light of a non-zero radius (exported as its "radius"). Writes the scene JSON;
the exporter's notes go to standard output. No render.

    blender -b --factory-startup --python scripts/blender/unmappable_scene.py -- --out scene.json
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import export_scene  # noqa: E402
import make_fixtures  # noqa: E402


def build_unmappable_scene():
    scene = make_fixtures.build_scene(32, 24)
    world = versions.node_tree(scene.world)
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
    noise = red.nodes.new("ShaderNodeTexNoise")
    red.links.new(noise.outputs["Color"], principled.inputs["Base Color"])

    blue = versions.node_tree(bpy.data.materials["blue"])
    glass = blue.nodes.new("ShaderNodeBsdfGlass")
    blue.links.new(glass.outputs["BSDF"], blue.nodes["Material Output"].inputs["Surface"])
    return scene


def main():
    out = sys.argv[sys.argv.index("--") + 1:][1]
    scene = build_unmappable_scene()
    export_scene.write_json(export_scene.scene_json(scene, "quadratic"), out)


if __name__ == "__main__":
    main()
