// G-buffers: read from EXR, or built from the caller's NumPy arrays; planes seen as arrays.
#include <optional>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "gbuffer/gbuffer.h"

namespace phongcl::python {

namespace {

std::string shape_of(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

void require_shape(const FloatArray& array, const char* name, py::ssize_t height, py::ssize_t width, int channels) {
  const bool ok = channels == 1 ? array.ndim() == 2 && array.shape(0) == height && array.shape(1) == width
                                : array.ndim() == 3 && array.shape(0) == height && array.shape(1) == width &&
                                      array.shape(2) == channels;
  if (!ok)
    throw py::value_error(std::string(name) + " must have shape (" + std::to_string(height) + ", " +
                          std::to_string(width) + (channels == 1 ? "" : ", " + std::to_string(channels)) +
                          "), got " + shape_of(array));
}

// (H, W, 3) interleaved into three planes.
Planes3 planes_from(const FloatArray& array) {
  const std::size_t pixels = static_cast<std::size_t>(array.shape(0) * array.shape(1));
  const float* data = array.data();
  Planes3 planes;
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) planes[c][i] = data[3 * i + c];
  }
  return planes;
}

py::array_t<float> interleaved(const GBuffer& g, const Planes3& planes) {
  py::array_t<float> out({g.height, g.width, 3});
  float* data = out.mutable_data();
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) data[3 * i + c] = planes[c][i];
  return out;
}

// A read-only view of one of the G-buffer's planes as (H, W), kept alive by the G-buffer object.
py::array plane_view(const py::object& owner, const GBuffer& g, const Plane& plane) {
  py::array_t<float> view({g.height, g.width}, {g.width * sizeof(float), sizeof(float)}, plane.data(), owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

GBuffer from_arrays(const FloatArray& P, const FloatArray& N, const FloatArray& material,
                    const std::optional<FloatArray>& alpha, const std::optional<FloatArray>& ka,
                    const std::optional<FloatArray>& kd, const std::optional<FloatArray>& ks,
                    const std::optional<FloatArray>& shininess) {
  if (P.ndim() != 3) throw py::value_error("P must have shape (H, W, 3), got " + shape_of(P));
  const py::ssize_t height = P.shape(0), width = P.shape(1);
  require_shape(P, "P", height, width, 3);
  require_shape(N, "N", height, width, 3);
  require_shape(material, "material", height, width, 1);
  GBuffer g;
  g.width = static_cast<int>(width);
  g.height = static_cast<int>(height);
  g.data_window = g.display_window = PixelWindow{0, 0, g.width - 1, g.height - 1};
  g.position = planes_from(P);
  g.normal = planes_from(N);
  g.material.assign(material.data(), material.data() + g.pixel_count());
  if (alpha) {
    require_shape(*alpha, "alpha", height, width, 1);
    for (std::size_t i = 0; i < g.pixel_count(); ++i)
      if (alpha->data()[i] == 0.0f) g.material[i] = -1.0f;  // background, as renderers mark it
  }
  for (auto [array, name, planes] : {std::tuple{&ka, "ka", &g.ka}, {&kd, "kd", &g.kd}, {&ks, "ks", &g.ks}}) {
    if (!*array) continue;
    require_shape(**array, name, height, width, 3);
    *planes = planes_from(**array);
  }
  if (shininess) {
    require_shape(*shininess, "shininess", height, width, 1);
    g.shininess.assign(shininess->data(), shininess->data() + g.pixel_count());
  }
  g.source = "<arrays>";
  return g;
}

}  // namespace

void bind_gbuffer(py::module_& module) {
  py::class_<GBuffer>(module, "GBuffer",
                      "A G-buffer: per-pixel position P, normal N and material index (negative: background), "
                      "optionally per-pixel ka, kd, ks, shininess. Built from arrays, it copies them once "
                      "into its planar layout (arrays of other dtypes or layouts are converted).")
      .def(py::init(&from_arrays), py::arg("P"), py::arg("N"), py::arg("material"), py::kw_only(),
           py::arg("alpha") = py::none(), py::arg("ka") = py::none(), py::arg("kd") = py::none(),
           py::arg("ks") = py::none(), py::arg("shininess") = py::none(),
           "P, N: (H, W, 3); material: (H, W) indices into the scene's materials; alpha (H, W): 0 marks "
           "background; ka, kd, ks (H, W, 3) and shininess (H, W) override the material table.")
      .def_property_readonly("width", [](const GBuffer& g) { return g.width; })
      .def_property_readonly("height", [](const GBuffer& g) { return g.height; })
      .def_property_readonly(
          "P", [](const GBuffer& g) { return interleaved(g, g.position); }, "Positions, float32 (H, W, 3) (a copy).")
      .def_property_readonly(
          "N", [](const GBuffer& g) { return interleaved(g, g.normal); }, "Normals, float32 (H, W, 3) (a copy).")
      .def_property_readonly(
          "material",
          [](const py::object& self) {
            const auto& g = self.cast<const GBuffer&>();
            return plane_view(self, g, g.material);
          },
          "Material indices, float32 (H, W): a view of the G-buffer's own plane, no copy.")
      .def_readonly("source", &GBuffer::source);

  module.def(
      "read_gbuffer", [](const std::filesystem::path& path) { return read_gbuffer(path); }, py::arg("path"),
      "Reads a G-buffer EXR in any layout (phongcl, Blender, AOV), detected from its channels; raises "
      "InputError naming the file on a missing channel or a bad file.");
}

}  // namespace phongcl::python
