// phongcl.Relighter: the resident G-buffer; shade() releases the GIL and writes straight into the
// NumPy array it returns (or the caller's).
#include <phongcl/relighter.hpp>

#include <algorithm>

#include <pybind11/stl.h>

#include "bindings.h"
#include "composite/relight_over.h"

namespace phongcl::python {

namespace {

// What `phongcl shade --device` takes: an index or a name; anything else is the caller's mistake,
// said in Python's terms rather than pybind11's cast message.
std::string device_selector(const py::object& device) {
  if (device.is_none()) return "";
  if (py::isinstance<py::int_>(device) && !py::isinstance<py::bool_>(device)) return std::to_string(device.cast<long long>());
  if (py::isinstance<py::str>(device)) return device.cast<std::string>();
  throw py::type_error("device must be None, an index (int) or a name (str), not " +
                       py::str(py::type::of(device).attr("__name__")).cast<std::string>() + " " +
                       py::repr(device).cast<std::string>());
}

py::array_t<float> shade(Relighter& relighter, const std::optional<py::array>& out) {
  const py::ssize_t height = relighter.height(), width = relighter.width();
  py::array_t<float> image;
  if (out) {
    const auto& array = *out;
    require_shape(array, "out", height, width, 4);
    if (!py::isinstance<py::array_t<float>>(array) || !(array.flags() & py::array::c_style) || !array.writeable())
      throw py::value_error("out must be a writeable C-contiguous float32 array");
    image = py::reinterpret_borrow<py::array_t<float>>(array);
  } else {
    image = py::array_t<float>({height, width, py::ssize_t{4}});
  }
  float* pixels = image.mutable_data();
  const std::size_t floats = static_cast<std::size_t>(image.size());
  {
    py::gil_scoped_release release;
    relighter.shade_into(pixels, floats);
  }
  return image;
}

py::array_t<float> array_of(const Image& image) {
  py::array_t<float> out({py::ssize_t{image.height}, py::ssize_t{image.width}, py::ssize_t{4}});
  std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
  return out;
}

// A composite as Python sees it: the image, and per light group what became of it.
py::dict relit_dict(const RelitOver& relit) {
  py::dict groups;
  for (const GroupEdit& edit : relit.edits) {
    py::dict group;
    group["change"] = to_string(edit.change);
    if (edit.change == GroupChange::scaled) group["scale"] = py::make_tuple(edit.scale.r, edit.scale.g, edit.scale.b);
    if (const auto fit = relit.fits.find(edit.group); fit != relit.fits.end()) {
      const GroupFit& f = fit->second;
      group["diffuse_gain"] = py::make_tuple(f.diffuse_gain.r, f.diffuse_gain.g, f.diffuse_gain.b);
      group["specular_gain"] = py::make_tuple(f.specular_gain.r, f.specular_gain.g, f.specular_gain.b);
      group["residual"] = f.residual;
    }
    groups[py::str(edit.group)] = group;
  }
  py::dict out;
  out["image"] = array_of(relit.image);
  out["groups"] = groups;
  return out;
}

// The composite over a render held by `compositor` of the relighter's scene as edited so far, or of `scene`.
py::dict relight_with(RenderCompositor& compositor, Relighter& relighter, const std::optional<Scene>& scene) {
  const Scene edited = scene ? *scene : relighter.scene();
  RelitOver relit;
  {
    py::gil_scoped_release release;
    relit = compositor.relight(relighter, edited);
  }
  return relit_dict(relit);
}

py::dict shade_over(Relighter& relighter, const std::string& render, const std::optional<Scene>& scene) {
  std::optional<RenderCompositor> compositor;
  {
    py::gil_scoped_release release;
    compositor.emplace(render);
  }
  return relight_with(*compositor, relighter, scene);
}

// The image and its terms as arrays; groups maps each light group's name to its image.
py::dict shade_terms(Relighter& relighter) {
  TermImages terms;
  Image image;
  {
    py::gil_scoped_release release;
    image = relighter.shade(terms);
  }
  py::dict groups;
  for (std::size_t g = 0; g < terms.groups.size(); ++g) groups[py::str(terms.group_names[g])] = array_of(terms.groups[g]);
  py::dict out;
  out["image"] = array_of(image);
  out["ambient"] = array_of(terms.ambient);
  out["diffuse"] = array_of(terms.diffuse);
  out["specular"] = array_of(terms.specular);
  out["groups"] = groups;
  return out;
}

py::dict timings(const Relighter& relighter) {
  const ShadeTimings t = relighter.last_timings();
  py::dict d;
  d["build_ms"] = t.build_ms;
  d["pack_ms"] = t.pack_ms;
  d["upload_ms"] = t.upload_ms;
  d["kernel_ms"] = t.kernel_ms;
  d["download_ms"] = t.download_ms;
  d["total_ms"] = t.total_ms;
  d["rebuilt"] = t.rebuilt;
  d["gbuffer_uploaded"] = t.gbuffer_uploaded;
  return d;
}

py::dict report(const Relighter& relighter) {
  const ShadeReport r = relighter.last_report();
  py::dict counts;
  counts["shaded"] = r.counts.shaded;
  counts["background"] = r.counts.background;
  counts["nonfinite_position"] = r.counts.nonfinite_position;
  counts["nonfinite_normal"] = r.counts.nonfinite_normal;
  counts["nonfinite_material"] = r.counts.nonfinite_material;
  py::dict d;
  d["counts"] = counts;
  d["tiles"] = r.tiles;
  d["culled"] = r.culled;
  if (r.culled) {
    py::dict culling;
    culling["tile_size"] = r.culling.tile_size;
    culling["tile_rows"] = r.culling.tile_rows;
    culling["shaded_tiles"] = r.culling.shaded_tiles;
    culling["mean_lights_per_tile"] = r.culling.mean_lights_per_tile();
    culling["mean_holding_per_tile"] = r.culling.mean_holding_per_tile();
    culling["max_lights_per_tile"] = r.culling.max_lights_per_tile;
    d["culling"] = culling;
  }
  d["kernel_summary"] = r.kernel_summary;
  d["recipe_reasons"] = r.recipe_reasons;
  d["build_options"] = r.build_options;
  d["warnings"] = r.warnings;
  d["shadows"] = r.shadows;
  return d;
}

}  // namespace

void bind_relighter(py::module_& module) {
  py::class_<Relighter>(module, "Relighter",
                        "A G-buffer kept in an OpenCL device's memory and shaded again after each change of "
                        "lights, materials or eye: a re-shade uploads only what changed, and the kernel is "
                        "rebuilt only when the recipe changes (e.g. the number of lights).")
      .def(py::init([](const Scene& scene, const GBuffer& gbuffer, const py::object& device,
                       const std::string& precision, bool specialise, int lanes, const std::string& shadows,
                       int shadow_steps, const std::string& shadow_thickness, int shadow_rays, bool terms) {
             RelighterOptions options{device_selector(device), parse_precision(precision), specialise, lanes};
             options.terms = terms;
             options.shadows = {parse_shadow_mode(shadows), shadow_steps, parse_shadow_thickness(shadow_thickness),
                                shadow_rays};
             check_options(options);  // before the device starts
             py::gil_scoped_release release;  // the kernel build and the packing take a while
             return Relighter(scene, gbuffer, options);
           }),
           py::arg("scene"), py::arg("gbuffer"), py::arg("device") = py::none(), py::arg("precision") = "precise",
           py::arg("specialise") = true, py::arg("lanes") = 0, py::arg("shadows") = "auto",
           py::arg("shadow_steps") = ShadowSettings{}.steps,
           py::arg("shadow_thickness") = format_shadow_thickness(ShadowSettings{}.thickness),
           py::arg("shadow_rays") = ShadowSettings{}.rays, py::arg("terms") = false,
           "device: None (the default device, as phongcl shade picks it), an index or a name; precision: "
           "'precise', 'fast', 'double' or 'half-storage'; specialise=False for the general kernel; lanes: "
           "pixels per work-item (0: the device's choice); shadows: how lights with shadows=True cast them, "
           "'auto' (geometry when the scene has objects, else screen), 'screen', 'geometry' or 'off'; "
           "shadow_steps and shadow_thickness ('0.25' world units or '6%' of the depth): the screen-space "
           "march's (docs/shadows.md); shadow_rays: geometry shadows' rays per pixel over an area light "
           "without its own (1: a hard shadow); terms=True for shade_terms().")
      .def("shade", &shade, py::arg("out") = py::none(),
           "Shades the frame: float32 (H, W, 4), RGBA, background alpha 0. With out=, writes into that "
           "array (C-contiguous float32 (H, W, 4)) and returns it. Releases the GIL while shading.")
      .def("shade_terms", &shade_terms,
           "Shades the frame with its terms (needs terms=True): a dict of float32 (H, W, 4) arrays, 'image', "
           "'ambient', 'diffuse', 'specular', and 'groups', each light group's name to its diffuse + specular "
           "(ambient + the groups + the ungrouped lights' light = image). Releases the GIL while shading.")
      .def("shade_over", &shade_over, py::arg("render"), py::arg("scene") = py::none(),
           "Relights the render itself (needs terms=True; docs/compositing.md): the EXR `render`'s Combined pass with "
           "each light group that the scene (default: this relighter's, as set_lights left it) changed since its "
           "\"rendered\" lights scaled or changed by phongcl's change of it. A dict: 'image' float32 (H, W, 4), and "
           "'groups', each group's name to {'change': 'unchanged', 'scaled' or 're-shaded', with 'scale', or the "
           "fit's 'diffuse_gain', 'specular_gain' and 'residual'}. Raises InputError naming the file or scene. "
           "Reads the render each call: RenderCompositor keeps it, and what it fitted, for a loop of edits.")
      .def(
          "set_lights", [](Relighter& r, const py::object& lights) { r.set_lights(lights_from_python(lights)); },
          py::arg("lights"),
          "New lights: Light objects or dicts in the scene file's form, whose vectors may be lists, tuples or "
          "NumPy arrays; linked materials must exist in the scene. Raises InputError or ValueError naming the "
          "entry (e.g. a NaN: must be finite).")
      .def(
          "set_frame",
          [](Relighter& r, const Scene& scene, const GBuffer& gbuffer) {
            GBuffer frame = gbuffer;  // copied while the GIL is held: the Python object may change after
            py::gil_scoped_release release;
            r.set_frame(scene, std::move(frame));
          },
          py::arg("scene"), py::arg("gbuffer"),
          "The next frame of a sequence: its scene (camera, lights, materials) and G-buffer, of any size. "
          "The kernels and device buffers are kept (a kernel is built again only where the recipe changes). "
          "Raises InputError or ValueError as the constructor does, and then keeps the frame it had.")
      .def(
          "set_area_lights",
          [](Relighter& r, const py::object& lights) { r.set_area_lights(area_lights_from_python(lights)); },
          py::arg("lights"),
          "New area lights, replacing every one: AreaLight objects or dicts in the scene file's form ({'type': "
          "'area', 'shape': 'rect' or 'disk', 'position', 'direction', 'size', ...}). Raises InputError or "
          "ValueError naming the entry.")
      .def(
          "set_environment",
          [](Relighter& r, const py::object& environment) { r.set_environment(environment_from_python(environment)); },
          py::arg("environment"),
          "The world's light, a dict in the scene file's form ({'type': 'environment', 'color': [r, g, b]} or "
          "'file': an equirect EXR, with 'rotation', 'strength', 'rays', 'shadows', 'group'), or None to remove "
          "it. Raises InputError naming the entry.")
      .def(
          "set_materials",
          [](Relighter& r, const py::object& materials) { r.set_materials(materials_from_python(materials)); },
          py::arg("materials"), "A new material table: Material objects or dicts in the scene file's form.")
      .def(
          "set_camera_eye",
          [](Relighter& r, const std::array<double, 3>& eye) { r.set_camera_eye(to_vec3(eye)); }, py::arg("eye"),
          "A new eye position (the G-buffer is re-packed relative to it at the next shade).")
      .def_property_readonly("width", &Relighter::width)
      .def_property_readonly("height", &Relighter::height)
      .def_property_readonly(
          "scene", [](const Relighter& r) { return r.scene(); },  // a copy: set_frame replaces the held one
          "The scene with every change so far (a copy).")
      .def_property_readonly(
          "device", [](const Relighter& r) { return describe(r.device()); }, "The OpenCL device, in one line.")
      .def_property_readonly("kernel_summary", &Relighter::kernel_summary, "The kernel's recipe in one line.")
      .def_property_readonly("build_options", &Relighter::build_options)
      .def_property_readonly("last_timings", &timings,
                             "What the last shade() cost, in ms: build, pack, upload, kernel, download, total; "
                             "and whether the kernel was rebuilt and the G-buffer uploaded.")
      .def_property_readonly("last_report", &report,
                             "What the last shade() found, as phongcl shade prints it: pixel counts (shaded, "
                             "background, non-finite), launches (tiles), tiled culling, the kernel's recipe "
                             "with the reason for each decision, and warnings.");

  py::class_<RenderCompositor>(module, "RenderCompositor",
                                "A render held for relighting over it again and again (docs/compositing.md): its passes "
                                "read once, and each light group's fit and phongcl's light of it as rendered kept "
                                "between calls, so that a loop of edits costs one shade per changed group.")
      .def(py::init([](const std::filesystem::path& render) {
             py::gil_scoped_release release;
             return RenderCompositor(render);
           }),
           py::arg("render"), "Reads the EXR's Combined pass and every light group's pass; InputError naming the file.")
      .def("relight", &relight_with, py::arg("relighter"), py::arg("scene") = py::none(),
           "The composite as Relighter.shade_over returns it, of `scene` (default: the relighter's, as "
           "set_lights left it); the relighter needs terms=True.")
      .def_property_readonly("render", [](const RenderCompositor& c) { return c.file().string(); });

  module.def(
      "devices",
      [] {
        std::vector<std::string> names;
        for (const DeviceInfo& info : available_devices()) names.push_back(describe(info));
        return names;
      },
      "Every OpenCL device, in the order Relighter(device=N) counts them.");
}

}  // namespace phongcl::python
