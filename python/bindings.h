#pragma once
// The phongcl Python module, one binder per part of the API (python/*.cpp).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "color/color_config.h"
#include "scene/scene.h"

namespace phongcl::python {

namespace py = pybind11;

// A C-contiguous float32 array, converted from other dtypes and layouts (one copy) where needed.
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// "(480, 640, 3)": an array's shape as NumPy prints it.
std::string shape_of(const py::array& array);
// ValueError "<name> must have shape (H, W[, C]), got ..." unless the array is (height, width),
// for channels 1, or (height, width, channels).
void require_shape(const py::array& array, const std::string& name, py::ssize_t height, py::ssize_t width,
                   int channels);

inline std::array<double, 3> to_array(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
inline glm::dvec3 to_vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// Light or Material objects, or dicts in the scene file's form (InputError names the bad entry).
std::vector<Light> lights_from_python(const py::handle& lights);
std::vector<AreaLight> area_lights_from_python(const py::handle& lights);
std::vector<Material> materials_from_python(const py::handle& materials);
// None, or a dict in the scene file's form ({'type': 'environment', 'color' or 'file', ...}); a
// relative 'file' is taken from the working directory.
std::optional<EnvironmentLight> environment_from_python(const py::handle& environment);

// The config `--ocio WHICH` would load (color/color_config.h), loaded once per process: views
// compiled for one image are ready for the next.
const ColorConfig& color_config(const std::string& which);

void bind_scene(py::module_& module);
void bind_gbuffer(py::module_& module);
void bind_images(py::module_& module);
void bind_relighter(py::module_& module);

}  // namespace phongcl::python
