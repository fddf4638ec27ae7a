// G-buffers: read from EXR, or built from the caller's NumPy arrays (read in place through a
// GBufferView); planes seen as arrays.
#include <phongcl/gbuffer_view.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "exr/exr_channels.h"
#include "gbuffer/gbuffer.h"

namespace phongcl::python {

namespace {

// float32 in any memory layout, read in place through its strides; other dtypes are converted.
using StridedFloats = py::array_t<float, py::array::forcecast>;

// Strides in whole floats, none zero (ChannelView reads a zero row stride as "rows packed"); a
// broadcast or byte-offset array is copied into a C-contiguous one first.
StridedFloats readable(const StridedFloats& array) {
  for (py::ssize_t d = 0; d < array.ndim(); ++d)
    if (array.strides(d) == 0 || array.strides(d) % static_cast<py::ssize_t>(sizeof(float)) != 0)
      return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
  return array;
}

// Channel c of an (H, W, C) array, or the (H, W) array itself for c < 0, in place.
ChannelView channel(const StridedFloats& array, int c) {
  const auto in_floats = [&](int d) { return static_cast<std::ptrdiff_t>(array.strides(d)) / std::ptrdiff_t{sizeof(float)}; };
  return {array.data() + (c < 0 ? 0 : c * in_floats(2)), in_floats(1), in_floats(0)};
}

Vec3View channels3(const StridedFloats& array) { return {channel(array, 0), channel(array, 1), channel(array, 2)}; }

// The G-buffer keeps x, y and z in three planes, so (H, W, 3) is a copy; read-only, so that an
// assignment into it fails instead of changing nothing.
py::array_t<float> interleaved(const GBuffer& g, const Planes3& planes) {
  py::array_t<float> out({g.height, g.width, 3});
  float* data = out.mutable_data();
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) data[3 * i + c] = planes[c][i];
  out.attr("flags").attr("writeable") = false;
  return out;
}

// The command line's --max-pixels rule, before any array is converted (a broadcast array of
// float64 would otherwise be copied whole first).
void check_size(const py::array& P, std::uint64_t max_pixels) {
  if (P.ndim() != 3 || P.shape(2) != 3) throw py::value_error("P must have shape (H, W, 3), got " + shape_of(P));
  const auto height = static_cast<std::uint64_t>(P.shape(0)), width = static_cast<std::uint64_t>(P.shape(1));
  const std::uint64_t pixels = height * width;
  if (pixels > max_pixels || width > std::numeric_limits<int>::max() || height > std::numeric_limits<int>::max())
    throw py::value_error("GBuffer of " + std::to_string(width) + " x " + std::to_string(height) + " = " +
                          std::to_string(pixels) + " pixels: more than max_pixels=" + std::to_string(max_pixels) +
                          " (the default is 16384 x 16384; pass a larger max_pixels to allow it)");
}

// A read-only view of one of the G-buffer's planes as (H, W), kept alive by the G-buffer object.
py::array plane_view(const py::object& owner, const GBuffer& g, const Plane& plane) {
  py::array_t<float> view({g.height, g.width}, {g.width * sizeof(float), sizeof(float)}, plane.data(), owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

// An ndarray as it is (a view: a broadcast array stays small), anything else array-like made one.
py::array as_array(const py::object& value, const char* name) {
  py::array array = py::array::ensure(value);
  if (!array) throw py::type_error(std::string(name) + " must be an array-like of numbers");
  return array;
}

// Arrays come in as they are (no conversion to float32 yet): the size is checked first.
GBuffer from_arrays(const py::object& P_arg, const py::object& N_in, const py::object& material_in,
                    const std::optional<py::object>& alpha, const std::optional<py::object>& ka,
                    const std::optional<py::object>& kd, const std::optional<py::object>& ks,
                    const std::optional<py::object>& shininess, std::uint64_t max_pixels) {
  const py::array P_in = as_array(P_arg, "P");
  check_size(P_in, max_pixels);
  const py::ssize_t height = P_in.shape(0), width = P_in.shape(1);
  GBufferView view;
  view.width = static_cast<int>(width);
  view.height = static_cast<int>(height);
  // Held here until make_gbuffer has read them (converted arrays are temporaries).
  std::vector<StridedFloats> held;
  const auto take = [&](const py::object& value, const char* name, int channels) {
    const py::array array = as_array(value, name);
    require_shape(array, name, height, width, channels);
    return held.emplace_back(readable(StridedFloats::ensure(array)));
  };
  view.position = channels3(take(P_in, "P", 3));
  view.normal = channels3(take(N_in, "N", 3));
  view.material = channel(take(material_in, "material", 1), -1);
  if (alpha) view.alpha = channel(take(*alpha, "alpha", 1), -1);
  if (ka) view.ka = channels3(take(*ka, "ka", 3));
  if (kd) view.kd = channels3(take(*kd, "kd", 3));
  if (ks) view.ks = channels3(take(*ks, "ks", 3));
  if (shininess) view.shininess = channel(take(*shininess, "shininess", 1), -1);
  GBuffer gbuffer = make_gbuffer(view);
  gbuffer.source = "<arrays>";
  return gbuffer;
}

}  // namespace

void bind_gbuffer(py::module_& module) {
  py::class_<GBuffer>(module, "GBuffer",
                      "A G-buffer: per-pixel position P, normal N and material index (negative: background), "
                      "optionally per-pixel ka, kd, ks, shininess. Built from arrays, it reads float32 arrays "
                      "in place through their strides (any layout) and copies them once into its planar "
                      "layout; arrays of other dtypes are converted first.")
      .def(py::init(&from_arrays), py::arg("P"), py::arg("N"), py::arg("material"), py::kw_only(),
           py::arg("alpha") = py::none(), py::arg("ka") = py::none(), py::arg("kd") = py::none(),
           py::arg("ks") = py::none(), py::arg("shininess") = py::none(),
           py::arg("max_pixels") = exr::kDefaultMaxPixels,
           "P, N: (H, W, 3); material: (H, W) indices into the scene's materials; alpha (H, W): 0 marks "
           "background; ka, kd, ks (H, W, 3) and shininess (H, W) override the material table. More than "
           "max_pixels pixels (default 16384 x 16384, as phongcl shade --max-pixels) is a ValueError, raised "
           "before any array is converted.")
      .def_property_readonly("width", [](const GBuffer& g) { return g.width; })
      .def_property_readonly("height", [](const GBuffer& g) { return g.height; })
      .def_property_readonly(
          "P", [](const GBuffer& g) { return interleaved(g, g.position); },
          "Positions, float32 (H, W, 3): a read-only copy (the G-buffer stores planes); to change them, build a "
          "new GBuffer.")
      .def_property_readonly(
          "N", [](const GBuffer& g) { return interleaved(g, g.normal); },
          "Normals, float32 (H, W, 3): a read-only copy, as P.")
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
