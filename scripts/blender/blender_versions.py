"""Every Blender convention the exporter and the scene builders depend on that changed between the
versions phongcl is checked with (3.4, 4.3, 5.2; docs/formats.md "From a Blender scene"), decided here by
bpy.app.version and nowhere else. Each entry names where the change is recorded: Blender's source
(file and function) or the release notes' Python API page (developer.blender.org/docs/release_notes/
<version>/python_api/). A new Blender that changes one more thing gets one more entry here.
"""
import math

import bpy

VERSION = bpy.app.version


def at_least(major, minor=0):
    return VERSION >= (major, minor, 0)


# Shadows. 4.0 moved a light's "cast shadow" from the Cycles add-on's light.cycles.cast_shadow to
# Light.use_shadow (release notes 4.0, Python API: "cycles.cast_shadow ... moved to Light.use_shadow";
# rna_light.cc rna_def_light, "use_shadow").
def casts_shadow(light_data):
    if at_least(4):
        return bool(light_data.use_shadow)
    return bool(light_data.cycles.cast_shadow)


def set_casts_shadow(light_data, value):
    if at_least(4):
        light_data.use_shadow = value
    else:
        light_data.cycles.cast_shadow = value


# Principled BSDF v1 (3.x) and v2 (4.0+; release notes 4.0, Cycles "Principled BSDF"): the exporter maps
# each to phongcl's principled material of that version, whose inputs differ (3.x's Specular and scalar
# Specular Tint; 4.x's IOR, Specular IOR Level and Specular Tint colour; docs/shading.md "Principled v2"
# reads 4.x's svm_node_closure_bsdf()).
# 4.0 also renamed "Emission" to "Emission Color" and "Subsurface" to "Subsurface Weight".
PRINCIPLED_EMISSION = "Emission Color" if at_least(4) else "Emission"

# Oren-Nayar. 4.3 replaced the Diffuse BSDF's Oren-Nayar by Fujii's improved model with OpenPBR's
# multiple scattering (closure/bsdf_oren_nayar.h) and gave the Principled BSDF the Diffuse Roughness
# input that takes it (svm/closure.h, CLOSURE_BSDF_PRINCIPLED_ID): phongcl's principled version 2 has
# that model, not the older one 3.x and 4.0 to 4.2 render a rough Diffuse BSDF with.
IMPROVED_OREN_NAYAR = at_least(4, 3)


def principled_emits(node):
    """True where the Principled BSDF emits light (phongcl has no emissive materials)."""
    emission = node.inputs[PRINCIPLED_EMISSION]
    strength = node.inputs["Emission Strength"]
    return (strength.is_linked or strength.default_value > 0.0) and (emission.is_linked or max(emission.default_value[:3]) > 0.0)


# Area lights. The radiance of an area light of P watts and area A:
#   3.x  P / (4 A)   (intern/cycles/kernel/light/light.h: eval_fac = 0.25 * invarea; measured with 3.4.1
#                     to 5e-4, docs/shading.md "Area lights")
#   4.0+ P / (pi A)  (intern/cycles/kernel/light/area.h, area_light_eval(): eval_fac = M_1_PI_F * invarea,
#                     read in the Cycles kernel source Debian's 4.3.2 ships in scripts/addons_core/cycles/source)
# so 4.x area lights exported with 3.x's factor came out at pi/4 of Cycles' light.
AREA_RADIANCE_PER_WATT = 1.0 / math.pi if at_least(4) else 0.25

# Spot lights. Cycles 3.x multiplies a spot's light by the cosine to its axis (spot_light_attenuation() in
# intern/cycles/kernel/light/common.h returns dot(dir, N) times the smoothstep); 4.0 dropped the factor
# (intern/cycles/kernel/light/spot.h, spot_light_attenuation(): the smoothstep only, read in 4.3.2's source).
SPOT_COSINE_POWER = None if at_least(4) else 1

# Point and spot radius (shadow_soft_size): 3.x lights from a disk of that radius facing the shaded point,
# 4.0 made them spheres with "soft falloff" (Light.use_soft_falloff, on by default;
# intern/cycles/kernel/light/point.h); with a radius of 0 both are a point. phongcl takes it as "radius".
def point_radius(light_data):
    return light_data.shadow_soft_size


# Render output. 5.0 splits the file format: an image's media type is chosen first and only the formats of
# that media type are then valid (release notes 5.0, Python API: ImageFormatSettings.media_type;
# "OPEN_EXR_MULTILAYER" needs media_type = "MULTI_LAYER_IMAGE").
def set_multilayer_exr(settings):
    if at_least(5):
        settings.media_type = "MULTI_LAYER_IMAGE"
    settings.file_format = "OPEN_EXR_MULTILAYER"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"


# The compositor. 5.0 removed Scene.node_tree and Scene.use_nodes for the compositor: the scene's
# compositor is a node group, Scene.compositing_node_group (release notes 5.0, Python API, "Compositor").
# In 5.0 the group has no Render Layers or output node until one is added, and a File Output node's
# inputs are file_output_items (CompositorNodeOutputFile) rather than layer_slots.
def compositor_tree(scene, create=True):
    """The scene's compositor node tree (made when create and missing), or None."""
    if at_least(5):
        tree = scene.compositing_node_group
        if tree is None and create:
            tree = bpy.data.node_groups.new("Compositor", "CompositorNodeTree")
            scene.compositing_node_group = tree
        return tree
    if create:
        scene.use_nodes = True
    return scene.node_tree if scene.use_nodes else None


# 5.0 also replaced the Composite node by the compositor group's Group Output, and named the Alpha Over
# node's inputs Background and Foreground (3.x and 4.x: Fac, Image, Image; release notes 5.0, Python API,
# "Compositor").
def composite_input(tree):
    """The socket whose image a render of the scene writes."""
    if at_least(5):
        tree.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
        return tree.nodes.new("NodeGroupOutput").inputs[0]
    return tree.nodes.new("CompositorNodeComposite").inputs[0]


def alpha_over_inputs(node):
    """An Alpha Over node's (background, foreground) inputs."""
    if at_least(5):
        return node.inputs["Background"], node.inputs["Foreground"]
    return node.inputs[1], node.inputs[2]


def disable_compositor(scene):
    if at_least(5):
        scene.compositing_node_group = None
    else:
        scene.use_nodes = False


def render_layers_node(tree):
    for node in tree.nodes:
        if node.type == "R_LAYERS":
            return node
    return tree.nodes.new("CompositorNodeRLayers")


def add_file_output_inputs(node, sockets):
    """Makes the File Output node's inputs, one per (name, socket it is fed by), in that order
    (layer_slots before 5.0; 5.x's file_output_items are typed like the socket feeding them)."""
    if at_least(5):
        node.file_output_items.clear()
        for name, socket in sockets:
            node.file_output_items.new({"VALUE": "FLOAT"}.get(socket.type, socket.type), name)
    else:
        node.layer_slots.clear()
        for name, _ in sockets:
            node.layer_slots.new(name)


# 5.0 names the Render Layers node's pass outputs by the passes' full names, as its EXRs do (release notes
# 5.0, Python API, "Compositor"; the 3.x/4.x short names are the EXR channel names of those versions).
RENDER_LAYER_OUTPUTS = {"IndexMA": "Material Index", "DiffCol": "Diffuse Color", "GlossCol": "Glossy Color",
                        "IndexOB": "Object Index", "DiffDir": "Diffuse Direct"} if at_least(5) else {}


def render_layer_output(node, short_name):
    """The Render Layers node's output of a pass named by its short (3.x) name."""
    return node.outputs[RENDER_LAYER_OUTPUTS.get(short_name, short_name)]


def set_file_output_path(node, directory, prefix):
    """Where a File Output node writes: directory/prefix<frame> (5.0 split base_path into directory and
    file_name, release notes 5.0, Python API, "Compositor")."""
    if at_least(5):
        node.directory, node.file_name = directory, prefix
    else:
        node.base_path = directory + "/" + prefix


# Materials' and worlds' node trees. 5.0 deprecated Material.use_nodes and World.use_nodes (release notes
# 5.0, Python API: "use_nodes ... deprecated, always true"): a 5.x node tree is always used.
def node_tree(id_data):
    """The node tree a material or world renders with, or None where it renders without one."""
    if not at_least(5) and not id_data.use_nodes:
        return None
    return id_data.node_tree


def use_nodes(id_data):
    """Gives a new material or world its default node tree (5.x: it has one already)."""
    if not at_least(5):
        id_data.use_nodes = True
    elif id_data.node_tree is None:
        id_data.use_nodes = True  # deprecated but still makes the tree in 5.x
    return id_data.node_tree


# EEVEE. 4.2 replaced EEVEE by "EEVEE Next", engine "BLENDER_EEVEE_NEXT"; 5.0 named it "BLENDER_EEVEE"
# again (release notes 4.2 and 5.0, Python API: RenderSettings.engine).
EEVEE_ENGINE = "BLENDER_EEVEE_NEXT" if (4, 2, 0) <= VERSION < (5, 0, 0) else "BLENDER_EEVEE"
