"""Writes phongcl's scene JSON from a .blend, and with --render the G-buffer EXR phongcl reads.

    blender -b file.blend --python scripts/blender/export_scene.py -- --out scene.json [--render gbuffer.exr]
        [--samples N] [--falloff quadratic|none] [--geometry DIR]

Conventions (docs/formats.md "Renderers' G-buffers", "From a Blender scene"). What differs between Blender
versions (3.4 through 5.x) is decided in blender_versions.py, each with its source; below, "3.x" and "4.0+"
name those cases.
- Camera: eye, forward (-Z) and up (+Y) of the camera's world matrix; the vertical field of view
  from Blender's own view frame (Camera.view_frame), which applies the sensor fit: under AUTO the
  sensor width spans the larger image side, so camera.data.angle_y is not the vertical fov of a
  landscape frame. Lens shift and non-square pixels have no phongcl camera: refused.
- Lights: Cycles lights a Lambertian surface of albedo rho with a point light of P watts as
  rho * cos * P / (4 pi^2 d^2) (radiant intensity P / 4pi, BSDF rho / pi), and with a sun of S W/m^2
  as rho * cos * S / pi, so phongcl's Li (kd * n.l * Li) is colour * P / (4 pi^2) (times 1/d^2) and
  colour * S / pi. Point and spot lights fall off with 1/d^2 in Blender, so they get phongcl's
  "falloff": "quadratic" (--falloff none instead takes each light's colour at its distance to the
  centre of the visible meshes). A spot's cone: Cycles lights where cos(angle to the axis) exceeds
  cos(spot_size/2) and smoothsteps over the spot_blend fraction of 1 - cos(spot_size/2) above it,
  in cosines, as phongcl's penumbra does, so cone_angle_deg is the angle whose cosine ends that
  blend and penumbra_angle_deg the rest of spot_size/2; inside the cone Cycles 3.x also multiplies by
  that cosine, so Blender 3.x spots get "cosine_power": 1 (4.0 dropped the factor). A point or spot's
  radius (shadow_soft_size) becomes its "radius" and a sun's angle its "angle" (degrees): phongcl casts
  their soft shadows (docs/shadows.md "Soft shadows"), while its unshadowed light stays a point's or a
  parallel light's; Cycles 3.x lights from a disk of that radius facing the point (dimmer by about
  d^2 / (d^2 + r^2) close to it), 4.0+ from a sphere (a point's light wherever all of it is above the
  horizon), so a note says so where the radius is more than a tenth of the distance to the meshes' centre.
- Area lights (square, rectangle, disk; ellipses are skipped with a note): Cycles 3.x gives an area
  light of P watts and area A the radiance P / (4 A) (kernel/light/light.h: eval_fac = 0.25 *
  invarea, strength = colour * energy; measured with Blender 3.4.1 under a square, a rectangle and
  a disk to 5e-4), Cycles 4.0+ P / (pi A) (kernel/light/area.h), and a Lambertian surface receives
  rho / pi times that radiance times the cosine-weighted solid angle; phongcl's area colour folds the
  1/pi in, so it is colour * P / (4 pi A) for 3.x and colour * P / (pi^2 A) for 4.0+.
  The emitting side is the light's -Z, the rect's height runs along its +Y, and the sizes are
  scaled by the object's scale as Cycles does. An area light that casts shadows in Cycles gets
  "shadows": true: a soft shadow with phongcl's --shadows geometry, a hard one from its centre in
  screen space.
- Materials by pass index (Material.pass_index): a Principled BSDF of Blender 2.8 to 3.6 becomes
  phongcl's "principled" material, version 1, with its base colour, metallic, roughness, specular and
  specular tint (docs/shading.md "Principled"; subsurface, sheen, clearcoat, transmission and
  anisotropy left out with a note where set). One of 4.0+ becomes version 2 (IOR, Specular IOR Level, the
  Specular Tint colour, 4.3's Diffuse Roughness: Cycles' Oren-Nayar; coat, sheen, transmission, subsurface,
  anisotropy and thin film left out with a note where set; docs/shading.md "Principled v2").
  A Diffuse BSDF gives kd = its colour and a material without nodes its viewport colour, both with ks = 0: no
  specular lobe. A Diffuse BSDF with a roughness is Oren-Nayar's on 4.3+ (a principled version 2 of IOR 1 and
  metallic 0: the diffuse alone), Lambert's with a note before. ka = kd. Indices no material uses get a grey material. The shader is the one
  linked to the active Material Output's Surface; any other shader, a socket fed by a node (a
  texture), and emission are not mapped: a note names the material, the node and the value exported
  instead.
- The world: its Background's colour and strength, or an equirectangular Environment Texture feeding
  it (the image, the Mapping node's Z rotation), become an {"type": "environment"} light, occluded by
  the scene as Cycles' world is, and "ambient" is 0 (world_light.py says how, and what gets a note).
- Shadows: a light that casts shadows in Cycles (light.cycles.cast_shadow in 3.x, Light.use_shadow in
  4.0+) gets "shadows": true.
- Light groups: a light's Object.lightgroup (Blender 3.2+) becomes its "group", area lights' too; --render
  adds each to the view layer's light groups, so Cycles writes its Combined_<group> pass.
- "rendered" keeps a copy of the lights as exported: edit "lights", and `phongcl shade --over` composites
  over the render with only the changed groups replaced (docs/compositing.md).
- --geometry DIR writes every visible mesh that casts shadows (Object.visible_shadow) as a
  world-space binary little-endian PLY in DIR, modifiers applied and triangulated, one file per
  object and material slot (DIR/<object>.<slot>.ply), and lists each as a {"type": "mesh"} object
  of its material's pass index, so phongcl's shadows trace the very triangles Cycles traced.
- --render enables the passes phongcl reads (Position, Normal, Depth, IndexMA, DiffCol, GlossCol)
  and renders a multilayer 32-bit EXR with Cycles on the CPU.
"""
import argparse
import array
import json
import math
import os
import re
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_versions as versions  # noqa: E402  every convention that differs between Blender versions
import world_light  # noqa: E402
from export_notes import note, rounded, unlinked_value  # noqa: E402

FALLBACK_MATERIAL = {"name": "unused pass index", "ka": [0.5] * 3, "kd": [0.5] * 3, "ks": [0.0] * 3, "shininess": 10.0}


def image_size(scene):
    r = scene.render
    return (r.resolution_x * r.resolution_percentage // 100, r.resolution_y * r.resolution_percentage // 100)


def camera_json(scene):
    camera = scene.camera
    if camera is None:
        raise SystemExit("export_scene: the scene has no camera")
    if camera.data.type != "PERSP":
        raise SystemExit("export_scene: camera '%s' is %s; phongcl needs a perspective camera" % (camera.name, camera.data.type))
    width, height = image_size(scene)
    frame = camera.data.view_frame(scene=scene)  # camera space corners, sensor fit and aspect applied
    xs, ys, depth = [v.x for v in frame], [v.y for v in frame], -frame[0].z
    if abs(max(xs) + min(xs)) > 1e-6 * max(xs) or abs(max(ys) + min(ys)) > 1e-6 * max(ys):
        raise SystemExit("export_scene: camera '%s' has a lens shift, which phongcl's camera cannot represent" % camera.name)
    half_width, half_height = max(xs) / depth, max(ys) / depth
    if abs(half_width / half_height - width / height) > 1e-4 * width / height:
        raise SystemExit("export_scene: non-square pixels (pixel aspect %g:%g) are not supported"
                         % (scene.render.pixel_aspect_x, scene.render.pixel_aspect_y))
    rotation = camera.matrix_world.to_3x3()
    eye = camera.matrix_world.translation
    forward = (rotation @ Vector((0.0, 0.0, -1.0))).normalized()
    up = (rotation @ Vector((0.0, 1.0, 0.0))).normalized()
    return {"eye": rounded(eye), "look_at": rounded(eye + forward), "up": rounded(up),
            "fov_y_deg": round(math.degrees(2.0 * math.atan(half_height)), 7), "width": width, "height": height}


def visible_meshes(scene):
    return [o for o in scene.objects if o.type == "MESH" and not o.hide_render]


def meshes_centre(scene):
    corners = [o.matrix_world @ Vector(c) for o in visible_meshes(scene) for c in o.bound_box]
    if not corners:
        return Vector((0.0, 0.0, 0.0))
    return sum(corners, Vector((0.0, 0.0, 0.0))) / len(corners)


# The smallest fully lit cone phongcl takes (0 < cone_angle_deg): a spot_blend of 1 has none.
MIN_CONE_DEG = 1e-3


def spot_cone(light):
    outer_half = light.data.spot_size / 2.0
    cos_outer = math.cos(outer_half)
    cos_inner = cos_outer + (1.0 - cos_outer) * light.data.spot_blend
    inner_half = max(math.acos(min(cos_inner, 1.0)), math.radians(MIN_CONE_DEG / 2.0))
    axis = light.matrix_world.to_3x3() @ Vector((0.0, 0.0, -1.0))
    cone = {"type": "spot", "direction": rounded(axis.normalized()),
            "cone_angle_deg": round(math.degrees(2.0 * inner_half), 6),
            "penumbra_angle_deg": round(max(math.degrees(outer_half - inner_half), 0.0), 6)}
    if versions.SPOT_COSINE_POWER is not None:
        cone["cosine_power"] = versions.SPOT_COSINE_POWER
    return cone


def with_shadow_and_group(light, entry):
    if versions.casts_shadow(light.data):
        entry["shadows"] = True
    # Blender 3.2+ light groups (Object.lightgroup): Cycles writes a Combined pass per group, phongcl
    # --aov a group.<name> layer. Blender allows letters, digits and '_' in the name, as phongcl does.
    group = getattr(light, "lightgroup", "")
    if group:
        entry["group"] = group
    return entry


def area_light_json(light):
    """A square, rectangle or disk as phongcl's area light (the module's docstring says why the colour)."""
    data = light.data
    if data.shape == "ELLIPSE":
        note("area light '%s' is an ellipse, which phongcl has not: skipped, no light exported for it" % light.name)
        return None
    if getattr(data, "spread", math.pi) < math.pi - 1e-6:
        note("area light '%s' has a spread below 180 degrees, which phongcl has not: skipped" % light.name)
        return None
    matrix = light.matrix_world.to_3x3()
    u, v, z = matrix.col[0], matrix.col[1], matrix.col[2]
    width = u.length * data.size
    height = v.length * (data.size_y if data.shape == "RECTANGLE" else data.size)
    entry = {"type": "area", "position": rounded(light.matrix_world.translation),
             "direction": rounded((-z).normalized())}
    if data.shape == "DISK":
        if abs(width - height) > 1e-6 * max(width, height):
            note("area light '%s' is a disk scaled into an ellipse, which phongcl has not: skipped" % light.name)
            return None
        entry.update({"shape": "disk", "size": round(width, 9)})
        area = math.pi / 4.0 * width * width
    else:
        entry.update({"shape": "rect", "up": rounded(v.normalized()), "size": [round(width, 9), round(height, 9)]})
        area = width * height
    if area <= 0.0:
        note("area light '%s' has no area (size %g x %g): skipped, no light exported for it" % (light.name, width, height))
        return None
    entry["color"] = rounded(Vector(data.color) * data.energy * versions.AREA_RADIANCE_PER_WATT / (math.pi * area))
    return with_shadow_and_group(light, entry)


def lights_json(scene, falloff):
    lights = []
    centre = meshes_centre(scene)
    for light in (o for o in scene.objects if o.type == "LIGHT" and not o.hide_render):
        data = light.data
        colour = Vector(data.color)
        if data.type == "SUN":
            direction = light.matrix_world.to_3x3() @ Vector((0.0, 0.0, -1.0))
            entry = {"type": "directional", "direction": rounded(direction.normalized()),
                     "color": rounded(colour * data.energy / math.pi)}
            if data.angle > 0.0:
                entry["angle"] = round(math.degrees(data.angle), 6)
            lights.append(with_shadow_and_group(light, entry))
            continue
        if data.type == "AREA":
            entry = area_light_json(light)
            if entry is not None:
                lights.append(entry)
            continue
        if data.type not in ("POINT", "SPOT"):
            note("light '%s' is an %s light, which phongcl has not: skipped" % (light.name, data.type.lower()))
            continue
        position = light.matrix_world.translation
        entry = {"type": "point", "position": rounded(position)}
        radius = versions.point_radius(data)
        if radius > 0.0:
            entry["radius"] = round(radius, 9)
            if radius > 0.1 * (position - centre).length:
                note("%s light '%s' has a radius of %.3g m, near the meshes: phongcl's light is a point's, its shadow "
                     "a sphere's" % (data.type.lower(), light.name, radius))
        if data.type == "SPOT":
            entry.update(spot_cone(light))
        intensity = colour * data.energy / (4.0 * math.pi ** 2)
        if falloff == "quadratic":
            entry["falloff"] = "quadratic"
        else:
            distance = max((position - centre).length, 1e-6)
            intensity = intensity / distance ** 2
            note("point light '%s' at %.3g from the meshes' centre, taken at that distance (no falloff)" % (light.name, distance))
        entry["color"] = rounded(intensity)
        lights.append(with_shadow_and_group(light, entry))
    return lights


def surface_shader(material):
    """The node feeding the material's active Material Output's Surface, or None (with a note) where there
    is none; None without a note where the material has no node tree (its viewport colour is used)."""
    tree = versions.node_tree(material)
    if tree is None:
        return None
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"]
    output = next((n for n in outputs if n.is_active_output), outputs[0] if outputs else None)
    if output is None or not output.inputs["Surface"].is_linked:
        note("material '%s' has no shader linked to a Material Output: exported its viewport colour, no specular"
             % material.name)
        return None
    return output.inputs["Surface"].links[0].from_node


def principled_v1_json(name, owner, node, base, metallic, roughness):
    """A 3.x Principled BSDF as phongcl's principled material (docs/shading.md "Principled"), with a note naming
    the inputs it leaves out (subsurface, sheen, clearcoat, transmission, anisotropy) where they are not 0, and
    for the Multiscatter GGX distribution, shaded as GGX."""
    for socket in ("Subsurface", "Sheen", "Clearcoat", "Transmission", "Anisotropic"):
        if node.inputs[socket].default_value != 0.0:
            note("%s: the Principled BSDF's %s is %.3g, which phongcl's principled material has not: left out"
                 % (owner, socket, node.inputs[socket].default_value))
    if node.distribution != "GGX":
        note("%s: the Principled BSDF's distribution is %s: shaded as GGX (single scattering)" % (owner, node.distribution))
    specular = unlinked_value(owner, node, "Specular", "value")
    tint = unlinked_value(owner, node, "Specular Tint", "value")
    clamp = lambda x, high=1.0: min(max(float(x), 0.0), high)  # noqa: E731
    ka = base * (1.0 - metallic)
    return {"name": name, "ka": rounded(ka), "specular_model": "principled", "version": 1, "base_color": rounded(base),
            "metallic": round(clamp(metallic), 6), "roughness": round(clamp(roughness), 6),
            "specular": round(clamp(specular, 12.0), 6), "specular_tint": round(clamp(tint), 6)}


def principled_v2_json(name, owner, node, base, metallic, roughness):
    """A 4.0+ Principled BSDF as phongcl's principled material, version 2 (docs/shading.md "Principled v2"), with
    a note naming the inputs it leaves out where they are set (subsurface, coat, sheen, transmission, anisotropy,
    thin film), and for the GGX distribution, shaded as Multiscatter GGX (the default). Diffuse Roughness (4.3 on)
    is Cycles' Oren-Nayar, phongcl's too."""
    for socket in ("Subsurface Weight", "Coat Weight", "Sheen Weight", "Transmission Weight", "Anisotropic",
                   "Thin Film Thickness"):
        if socket in node.inputs and node.inputs[socket].default_value != 0.0:
            note("%s: the Principled BSDF's %s is %.3g, which phongcl's principled material has not: left out"
                 % (owner, socket, node.inputs[socket].default_value))
    if node.distribution != "MULTI_GGX":
        note("%s: the Principled BSDF's distribution is %s: shaded as Multiscatter GGX (with its energy compensation)"
             % (owner, node.distribution))
    ior = unlinked_value(owner, node, "IOR", "value")
    if ior < 1.0:
        note("%s: the Principled BSDF's IOR is %.3g: exported as 1 (phongcl's index is at least 1)" % (owner, ior))
    level = unlinked_value(owner, node, "Specular IOR Level", "value")
    tint = Vector(unlinked_value(owner, node, "Specular Tint", "colour")[:3])
    clamp = lambda x, low=0.0, high=1.0: min(max(float(x), low), high)  # noqa: E731
    material = {"name": name, "ka": rounded(base * (1.0 - metallic)), "specular_model": "principled", "version": 2,
                "base_color": rounded(base), "metallic": round(clamp(metallic), 6), "roughness": round(clamp(roughness), 6),
                "ior": round(clamp(ior, 1.0, 1000.0), 6), "specular_ior_level": round(max(float(level), 0.0), 6),
                "specular_tint": rounded(Vector([max(c, 0.0) for c in tint]))}
    if "Diffuse Roughness" in node.inputs:
        diffuse_roughness = clamp(unlinked_value(owner, node, "Diffuse Roughness", "value"))
        if diffuse_roughness > 0.0:
            material["diffuse_roughness"] = round(diffuse_roughness, 6)
    return material


def rough_diffuse_json(name, base, roughness):
    """A 4.3+ Diffuse BSDF with a roughness: Cycles' Oren-Nayar of its colour, which is phongcl's principled
    version 2 without its specular layers (metallic 0, IOR 1: no dielectric lobe, nothing over the diffuse)."""
    return {"name": name, "ka": rounded(base), "specular_model": "principled", "version": 2, "base_color": rounded(base),
            "metallic": 0.0, "ior": 1.0, "diffuse_roughness": round(min(max(float(roughness), 0.0), 1.0), 6)}


def material_json(material):
    owner = "material '%s'" % material.name
    node = surface_shader(material)
    if node is None or node.type not in ("BSDF_PRINCIPLED", "BSDF_DIFFUSE"):
        if node is not None:
            note("%s: its surface shader '%s' (%s) is neither a Principled nor a Diffuse BSDF: exported its "
                 "viewport colour, no specular" % (owner, node.name, node.bl_idname))
        base = Vector(material.diffuse_color[:3])
        return {"name": material.name, "ka": rounded(base), "kd": rounded(base), "ks": [0.0] * 3, "shininess": 1.0}
    if node.type == "BSDF_DIFFUSE":
        base = Vector(unlinked_value(owner, node, "Color", "colour")[:3])
        roughness = unlinked_value(owner, node, "Roughness", "value")
        if roughness > 0.0 and versions.IMPROVED_OREN_NAYAR:
            return rough_diffuse_json(material.name, base, roughness)
        if roughness > 0.0:
            note("%s: the Diffuse BSDF's Roughness is %.3g (Blender before 4.3: the older Oren-Nayar), which phongcl "
                 "has not: exported as Lambert's" % (owner, roughness))
        return {"name": material.name, "ka": rounded(base), "kd": rounded(base), "ks": [0.0] * 3, "shininess": 1.0}
    base = Vector(unlinked_value(owner, node, "Base Color", "colour")[:3])
    metallic = unlinked_value(owner, node, "Metallic", "value")
    roughness = unlinked_value(owner, node, "Roughness", "value")
    if versions.principled_emits(node):
        note("%s: the Principled BSDF emits light, which phongcl's materials do not: emission left out" % owner)
    if not versions.at_least(4):
        return principled_v1_json(material.name, owner, node, base, metallic, roughness)
    return principled_v2_json(material.name, owner, node, base, metallic, roughness)


def materials_json(scene):
    by_index = {}
    for obj in visible_meshes(scene):
        for slot in obj.material_slots:
            material = slot.material
            if material is None:
                continue
            chosen = by_index.setdefault(material.pass_index, material)
            if chosen is not material:
                note("materials '%s' and '%s' share pass index %d: '%s' is used"
                     % (chosen.name, material.name, material.pass_index, chosen.name))
    if not by_index:
        return [dict(FALLBACK_MATERIAL)]
    return [material_json(by_index[i]) if i in by_index else dict(FALLBACK_MATERIAL) for i in range(max(by_index) + 1)]


def write_ply(path, vertices, triangles):
    """Binary little-endian PLY: float x y z, faces as uchar-counted int lists; written atomically."""
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(vertices) // 3, len(triangles) // 3))
    faces = bytearray()
    corners = array.array("i", triangles)
    if sys.byteorder != "little":
        corners.byteswap()
    raw = corners.tobytes()
    for t in range(len(triangles) // 3):
        faces += b"\x03" + raw[12 * t:12 * t + 12]
    coordinates = array.array("f", vertices)
    if sys.byteorder != "little":
        coordinates.byteswap()
    temp = path + ".tmp"
    with open(temp, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(coordinates.tobytes())
        out.write(faces)
    os.replace(temp, path)


def safe_name(name):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name)


def export_geometry(scene, directory, json_directory):
    """Each visible, shadow-casting mesh, evaluated (modifiers applied), in world space and triangulated,
    one PLY per object and material slot; returns the scene's "objects" entries for them."""
    os.makedirs(directory, exist_ok=True)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    objects = []
    for obj in visible_meshes(scene):
        if not obj.visible_shadow:
            note("mesh '%s' casts no shadow in Cycles: left out of --geometry" % obj.name)
            continue
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        try:
            mesh.transform(obj.matrix_world)
            mesh.calc_loop_triangles()
            by_slot = {}
            for triangle in mesh.loop_triangles:
                by_slot.setdefault(triangle.material_index, []).append(triangle.vertices)
            for slot, triangles in sorted(by_slot.items()):
                used = sorted({v for t in triangles for v in t})
                remap = {v: i for i, v in enumerate(used)}
                vertices = [c for v in used for c in mesh.vertices[v].co]
                corners = [remap[v] for t in triangles for v in t]
                path = os.path.join(directory, "%s.%d.ply" % (safe_name(obj.name), slot))
                write_ply(path, vertices, corners)
                material = obj.material_slots[slot].material if slot < len(obj.material_slots) else None
                objects.append({"type": "mesh", "file": os.path.relpath(os.path.abspath(path), json_directory),
                                "material": material.pass_index if material is not None else 0})
                note("wrote %s (%d triangles)" % (path, len(triangles)))
        finally:
            evaluated.to_mesh_clear()
    return objects


def scene_json(scene, falloff="none", gbuffer=None, objects=None, directory=None):
    """The scene's JSON document; `directory` is where it will be written (files it names are relative to
    it; default: the current directory)."""
    lights = lights_json(scene, falloff)
    # The world is the environment light, occluded as Cycles' is: no ambient term beside it.
    environment = world_light.environment_json(scene, os.path.abspath(directory or "."))
    if environment is not None:
        lights.append(environment)
    document = {"camera": camera_json(scene), "background": [0.0, 0.0, 0.0], "ambient": [0.0, 0.0, 0.0],
                "lights": lights, "materials": materials_json(scene)}
    if objects:
        document["objects"] = objects
    if gbuffer:
        document["gbuffer"] = gbuffer
    # The lights as rendered, kept apart from those the artist edits: `phongcl shade --over` tells by
    # them which light groups changed since the render.
    document["rendered"] = {"lights": json.loads(json.dumps(lights))}
    return document


def write_json(document, path):
    temp = path + ".tmp"
    # One line per camera, light and material: readable, and diffs stay small.
    lines = []
    for key, value in document.items():
        if isinstance(value, list) and value and isinstance(value[0], dict):
            items = ",\n".join("    " + json.dumps(item) for item in value)
            lines.append('  "%s": [\n%s\n  ]' % (key, items))
        elif key == "rendered":
            items = ",\n".join("      " + json.dumps(item) for item in value["lights"])
            lines.append('  "rendered": {"lights": [\n%s\n  ]}' % items if items else '  "rendered": {"lights": []}')
        else:
            lines.append("  %s: %s" % (json.dumps(key), json.dumps(value)))
    with open(temp, "w") as out:
        out.write("{\n" + ",\n".join(lines) + "\n}\n")
    os.replace(temp, path)


def enable_passes(view_layer, position=True, material_index=True):
    view_layer.use_pass_combined = True
    view_layer.use_pass_z = True
    view_layer.use_pass_normal = True
    view_layer.use_pass_diffuse_color = True
    view_layer.use_pass_glossy_color = True
    if position:
        view_layer.use_pass_position = True
    if material_index:
        view_layer.use_pass_material_index = True


def add_light_group_passes(scene, view_layer):
    """Cycles writes a Combined_<group> pass for each light group of the view layer (Blender 3.2+); a
    light's group that the layer lacks is added, so every exported "group" has its pass."""
    if not hasattr(view_layer, "lightgroups"):
        return
    owners = [("light '%s'" % o.name, o.lightgroup) for o in scene.objects if o.type == "LIGHT" and not o.hide_render]
    if scene.world is not None:
        owners.append(("world '%s'" % scene.world.name, scene.world.lightgroup))
    for owner, group in owners:
        if group and group not in view_layer.lightgroups:
            view_layer.lightgroups.add(name=group)
            note("light group '%s' of %s added to view layer '%s', so that its pass is rendered"
                 % (group, owner, view_layer.name))


def multilayer_exr(settings):
    versions.set_multilayer_exr(settings)


def render_gbuffer(scene, path, samples=None):
    """Renders the active view layer's passes to a multilayer EXR at `path` with Cycles on the CPU, at
    `samples` per pixel if given (the scene's own count is kept for the renders that follow)."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    kept = scene.cycles.samples
    if samples:
        scene.cycles.samples = samples
    enable_passes(bpy.context.view_layer)
    add_light_group_passes(scene, bpy.context.view_layer)
    multilayer_exr(scene.render.image_settings)
    scene.render.use_file_extension = False
    scene.render.filepath = os.path.abspath(path)
    bpy.ops.render.render(write_still=True)
    scene.cycles.samples = kept


def parse(argv):
    parser = argparse.ArgumentParser(prog="export_scene.py")
    parser.add_argument("--out", required=True, help="scene JSON to write")
    parser.add_argument("--render", help="also render the G-buffer EXR here (Cycles, CPU)")
    parser.add_argument("--samples", type=int, help="Cycles samples for --render (default: the file's)")
    parser.add_argument("--geometry", help="write the visible meshes as world-space PLY files in this directory and "
                        "list them as the scene's objects (exact shadows)")
    parser.add_argument("--falloff", choices=("none", "quadratic"), default="quadratic",
                        help="quadratic (default): point and spot lights fall off with 1/d^2 as in Blender; none: "
                             "each light's colour taken at its distance to the meshes' centre")
    return parser.parse_args(argv)


def main():
    args = parse(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    scene = bpy.context.scene
    gbuffer = None
    if args.render:
        render_gbuffer(scene, args.render, args.samples)
        gbuffer = os.path.relpath(os.path.abspath(args.render), os.path.dirname(os.path.abspath(args.out)))
    objects = None
    if args.geometry:
        objects = export_geometry(scene, args.geometry, os.path.dirname(os.path.abspath(args.out)))
    write_json(scene_json(scene, args.falloff, gbuffer, objects, os.path.dirname(os.path.abspath(args.out))), args.out)
    note("wrote " + args.out + (" and " + args.render if args.render else ""))


if __name__ == "__main__":
    main()
