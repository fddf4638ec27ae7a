"""The scene of the environment comparison (docs/formats.md "The world"): shadow_scene.py's spheres and box on
a ground, pure diffuse, no bounces, lit by the world alone, so that Cycles' Diffuse Direct pass holds all of
the world's light on a surface and phongcl's environment light is held to it. With --materials principled
the objects are Principled BSDFs instead (PRINCIPLED: a rough dielectric ground, a glossier red, a blue
metal) and the Glossy Direct and Color passes are rendered too, for the environment's specular. Two worlds:

    uniform  a Background colour times a strength
    hdri     an equirectangular float EXR this script draws (sky.exr, 256x128: a sky gradient, a darker
             ground and a sun disc of 4 degrees' radius), through a Mapping node rotating it by ROTATION_DEG
             about Z, fed by Texture Coordinate's Generated, so the check sees the rotation's sign

    blender -b --factory-startup --python scripts/blender/environment_scene.py -- --out DIR --world uniform|hdri
        [--width 160 --height 120] [--samples 1024] [--seed 1] [--materials diffuse|principled]

writes DIR/environment.blend, with export_scene.py (--geometry) DIR/scene.json, DIR/gbuffer.exr and
DIR/meshes/*.ply, then DIR/render.exr: Cycles' DiffDir, DiffCol, IndexOB (and the G-buffer's passes), every
sample at the pixel centre as in the G-buffer (box filter of 0.01 px), --samples per pixel of --seed.
"""
import argparse
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402
import exr_file  # noqa: E402
import export_scene  # noqa: E402
import principled_scene  # noqa: E402
import shadow_scene  # noqa: E402

UNIFORM_COLOUR, UNIFORM_STRENGTH = (0.6, 0.75, 1.0), 1.2
SKY_SIZE = (256, 128)
SUN_AZIMUTH_U, SUN_ELEVATION_DEG, SUN_RADIUS_DEG, SUN_RADIANCE = 0.3, 35.0, 4.0, 150.0
HDRI_STRENGTH, ROTATION_DEG = 1.5, 40.0
# shadow_scene.py's material name: base colour, metallic, roughness (Specular 0.5, no tint)
PRINCIPLED = {"ground": ((0.6, 0.6, 0.55), 0.0, 0.5), "red": ((0.8, 0.15, 0.1), 0.0, 0.3),
              "blue": ((0.15, 0.25, 0.8), 1.0, 0.4)}


def sky_rows(width, height):
    """The map, top row first: a zenith-to-horizon gradient, a darker ground below the horizon and a sun
    disc centred at image column SUN_AZIMUTH_U and SUN_ELEVATION_DEG (angles measured on the sphere)."""
    sun_azimuth = 2.0 * math.pi * SUN_AZIMUTH_U
    sun_elevation = math.radians(SUN_ELEVATION_DEG)
    cos_radius = math.cos(math.radians(SUN_RADIUS_DEG))
    rows = []
    for y in range(height):
        elevation = math.pi / 2.0 - math.pi * (y + 0.5) / height
        row = []
        for x in range(width):
            azimuth = 2.0 * math.pi * (x + 0.5) / width
            if elevation >= 0.0:
                t = math.sin(elevation)
                pixel = (0.9 - 0.6 * t, 0.95 - 0.45 * t, 1.0)
            else:
                pixel = (0.25, 0.2, 0.15)
            cos_to_sun = (math.sin(elevation) * math.sin(sun_elevation)
                          + math.cos(elevation) * math.cos(sun_elevation) * math.cos(azimuth - sun_azimuth))
            if cos_to_sun >= cos_radius:
                pixel = (SUN_RADIANCE, 0.9 * SUN_RADIANCE, 0.75 * SUN_RADIANCE)
            row.append(pixel)
        rows.append(row)
    return rows


def uniform_world(world):
    background = versions.node_tree(world).nodes["Background"]
    background.inputs["Color"].default_value = (*UNIFORM_COLOUR, 1.0)
    background.inputs["Strength"].default_value = UNIFORM_STRENGTH


def hdri_world(world, directory):
    path = os.path.join(directory, "sky.exr")
    exr_file.write(path, sky_rows(*SKY_SIZE))
    tree = versions.node_tree(world)
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = bpy.data.images.load(path)
    mapping = tree.nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(ROTATION_DEG))
    coordinates = tree.nodes.new("ShaderNodeTexCoord")
    tree.links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
    tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    background = tree.nodes["Background"]
    tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = HDRI_STRENGTH


def use_principled_materials(scene):
    """Each object's diffuse material swapped for the Principled one of its name, with its pass index."""
    for obj in scene.objects:
        if obj.type != "MESH":
            continue
        old = obj.data.materials[0]
        colour, metallic, roughness = PRINCIPLED[old.name]
        obj.data.materials[0] = principled_scene.principled_material(
            old.name + "-principled", colour, metallic, roughness, 0.5, 0.0, old.pass_index)
    layer = bpy.context.view_layer
    layer.use_pass_glossy_direct = True
    layer.use_pass_glossy_color = True


def main():
    parser = argparse.ArgumentParser(prog="environment_scene.py")
    parser.add_argument("--out", required=True)
    parser.add_argument("--world", choices=("uniform", "hdri"), required=True)
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=120)
    parser.add_argument("--samples", type=int, default=1024)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--materials", choices=("diffuse", "principled"), default="diffuse")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)

    def add_world():
        if args.world == "uniform":
            uniform_world(bpy.context.scene.world)
        else:
            hdri_world(bpy.context.scene.world, out)

    scene = shadow_scene.build_shadow_scene(args.width, args.height, add_world, args.samples)
    scene.cycles.seed = args.seed
    if args.materials == "principled":
        use_principled_materials(scene)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "environment.blend"))
    export_scene.render_gbuffer(scene, os.path.join(out, "gbuffer.exr"), samples=1)  # one sample: the centre
    objects = export_scene.export_geometry(scene, os.path.join(out, "meshes"), out)
    document = export_scene.scene_json(scene, "quadratic", "gbuffer.exr", objects, out)
    export_scene.write_json(document, os.path.join(out, "scene.json"))

    scene.render.filepath = os.path.join(out, "render.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
