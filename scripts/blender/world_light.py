"""The scene's world as phongcl's environment light (docs/formats.md "From a Blender scene", "The world"):

    Background (colour unlinked)                       {"type": "environment", "color", "strength"}
    Environment Texture -> Background Color           {"type": "environment", "file", "rotation", "strength"}
      (its Vector unlinked, or from a Mapping node fed by Texture Coordinate's Generated or by nothing)

"rotation" is the Mapping node's Z rotation in degrees (negated for a Mapping of type Texture, which
applies the inverse): Cycles looks the image up in the direction rotated by it. A Mapping's location
(type Point), X or Y rotation or scale has no phongcl counterpart: a note names it and it is left out.
"file" is relative to the scene JSON: the image's own file where that is a linear EXR on disk, else (packed,
generated, or another format: .hdr, .png) a float EXR copy written next to the JSON as <image>.exr,
8-bit sRGB pixels made linear as Cycles reads them. Anything else in the world's tree gets a note naming
its node, and the exported light is the socket's own value. A world in a light group (World.lightgroup,
3.2+) gives the light its "group". The world lights through geometry in Cycles, always: "shadows": true.
A black world (colour or strength 0) exports no light. The map's orientation stays Cycles' (the top row
+Z, the centre column +X: docs/formats.md "The world").
"""
import array
import math
import os
import re

import bpy

import blender_versions as versions
import exr_file
from export_notes import note, unlinked_value

# Colour spaces whose pixels Cycles takes as they are (linear Rec.709 in every checked version's OCIO
# configuration; 4.0 renamed "Linear" to "Linear Rec.709").
LINEAR_SPACES = ("Linear", "Linear Rec.709", "Non-Color", "Raw")


def _output_shader(world):
    tree = versions.node_tree(world)
    if tree is None:
        return None, tree
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_WORLD"]
    output = next((n for n in outputs if n.is_active_output), outputs[0] if outputs else None)
    if output is None or not output.inputs["Surface"].is_linked:
        return None, tree
    return output.inputs["Surface"].links[0].from_node, tree


def _feeding(socket):
    return socket.links[0].from_node if socket.is_linked else None


def _rotation_deg(owner, texture):
    """The Z rotation (degrees) the texture's Vector input applies, with a note for every other transform."""
    mapping = _feeding(texture.inputs["Vector"])
    if mapping is None:
        return 0.0
    if mapping.type != "MAPPING":
        note("%s: %s's Vector is fed by '%s' (%s), which phongcl cannot evaluate: the image taken unrotated"
             % (owner, texture.name, mapping.name, mapping.bl_idname))
        return 0.0
    source = mapping.inputs["Vector"].links[0] if mapping.inputs["Vector"].is_linked else None
    if source is not None and (source.from_node.type != "TEX_COORD" or source.from_socket.name != "Generated"):
        note("%s: %s's Vector is fed by '%s' (%s), not by Texture Coordinate's Generated: the image taken as if it were"
             % (owner, mapping.name, source.from_node.name, source.from_socket.name))
    sockets = {name: mapping.inputs[name] for name in ("Location", "Rotation", "Scale") if name in mapping.inputs}
    for name, socket in sockets.items():
        if socket.is_linked:
            note("%s: %s's %s is fed by '%s', which phongcl cannot evaluate: its own value taken"
                 % (owner, mapping.name, name, socket.links[0].from_node.name))
    rotation = sockets["Rotation"].default_value
    unmapped = []
    if mapping.vector_type in ("POINT", "TEXTURE") and any(abs(v) > 1e-6 for v in sockets["Location"].default_value):
        unmapped.append("location %s" % [round(v, 4) for v in sockets["Location"].default_value])
    if abs(rotation[0]) > 1e-6 or abs(rotation[1]) > 1e-6:
        unmapped.append("X, Y rotation %.4g, %.4g deg" % (math.degrees(rotation[0]), math.degrees(rotation[1])))
    if any(abs(v - 1.0) > 1e-6 for v in sockets["Scale"].default_value):
        unmapped.append("scale %s" % [round(v, 4) for v in sockets["Scale"].default_value])
    if unmapped:
        note("%s: %s's %s: phongcl rotates an environment about Z only; left out" % (owner, mapping.name, ", ".join(unmapped)))
    degrees = math.degrees(rotation[2])
    return -degrees if mapping.vector_type == "TEXTURE" else degrees


def _linear_rows(owner, image):
    """The image's RGB as linear floats, top row first (Blender's pixels run bottom to top)."""
    width, height = image.size
    pixels = array.array("f", bytes(4 * width * height * image.channels))
    image.pixels.foreach_get(pixels)
    space = image.colorspace_settings.name
    if space == "sRGB" and not image.is_float:
        pixels = array.array("f", (v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4 for v in pixels))
    elif space not in LINEAR_SPACES:
        note("%s: image '%s' is in colour space '%s': its pixels taken as linear" % (owner, image.name, space))
    stride = image.channels
    return [[tuple(pixels[(y * width + x) * stride + c] for c in range(3)) for x in range(width)]
            for y in reversed(range(height))]


def _image_file(owner, image, directory):
    """A path to the image as an EXR phongcl reads: its own file, or a copy written in `directory`."""
    own = os.path.abspath(bpy.path.abspath(image.filepath, library=image.library)) if image.filepath else ""
    if (image.source == "FILE" and image.packed_file is None and own.lower().endswith(".exr") and os.path.isfile(own)
            and image.colorspace_settings.name in LINEAR_SPACES):
        return own
    path = os.path.join(directory, re.sub(r"[^A-Za-z0-9_.-]", "_", image.name) + ".exr")
    exr_file.write(path, _linear_rows(owner, image))
    note("%s: image '%s' is %s: wrote its float EXR copy %s" % (owner, image.name,
         "packed" if image.packed_file is not None else "not an EXR file" if image.source == "FILE" else image.source.lower(),
         path))
    return path


def _texture_entry(owner, texture, directory):
    """{"file", "rotation"} of an equirectangular Environment Texture with an image, else None (with a note
    where it is an Environment Texture)."""
    if texture is None or texture.type != "TEX_ENVIRONMENT":
        return None
    if texture.image is None:
        note("%s: %s has no image (Cycles renders it magenta)" % (owner, texture.name))
        return None
    if texture.projection != "EQUIRECTANGULAR":
        note("%s: %s's projection is %s, phongcl reads equirectangular maps only"
             % (owner, texture.name, texture.projection.lower().replace("_", " ")))
        return None
    return {"file": os.path.relpath(_image_file(owner, texture.image, directory), directory),
            "rotation": round(_rotation_deg(owner, texture), 4)}


def environment_json(scene, directory):
    """The world's environment light entry, or None (with a note where the world lights but cannot be
    mapped); `directory` is the scene JSON's, which "file" is relative to."""
    world = scene.world
    if world is None:
        return None
    owner = "world '%s'" % world.name
    shader, tree = _output_shader(world)
    if tree is None:
        light, strength = {"color": world.color[:3]}, 1.0
    elif shader is None:
        note("%s has no shader linked to a World Output: exported no environment light" % owner)
        return None
    elif shader.type != "BACKGROUND":
        note("%s: its surface shader '%s' (%s) is not a Background: exported no environment light"
             % (owner, shader.name, shader.bl_idname))
        return None
    else:
        strength = unlinked_value(owner, shader, "Strength", "value")
        if strength <= 0.0:
            return None
        light = (_texture_entry(owner, _feeding(shader.inputs["Color"]), directory)
                 or {"color": unlinked_value(owner, shader, "Color", "colour")[:3]})
    if strength <= 0.0 or max(light.get("color", [1.0])) <= 0.0:
        return None  # a black world lights nothing
    entry = {"type": "environment"}
    if "color" in light:
        entry["color"] = [round(float(c), 7) for c in light["color"]]
    else:
        entry.update(light)
    entry["strength"] = round(float(strength), 7)
    entry["shadows"] = True
    if world.lightgroup:
        entry["group"] = world.lightgroup
    return entry
