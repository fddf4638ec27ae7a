// Images as NumPy arrays (H, W, 4) float32, RGBA: to and from EXR, to PNG through an OCIO display.
#include <map>
#include <mutex>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "color/display.h"
#include "image/image.h"

namespace phongcl::python {

const ColorConfig& color_config(const std::string& which) {
  static std::mutex mutex;
  static std::map<std::string, ColorConfig> loaded;
  std::lock_guard lock(mutex);
  if (const auto found = loaded.find(which); found != loaded.end()) return found->second;
  return loaded.emplace(which, ColorConfig::load(which)).first->second;
}

namespace {

Image image_from(const FloatArray& pixels) {
  if (pixels.ndim() != 3 || (pixels.shape(2) != 4 && pixels.shape(2) != 3))
    throw py::value_error("an image must be an array of shape (H, W, 4) or (H, W, 3)");
  const int channels = static_cast<int>(pixels.shape(2));
  Image image(static_cast<int>(pixels.shape(1)), static_cast<int>(pixels.shape(0)));
  const float* data = pixels.data();
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    for (int c = 0; c < channels; ++c) image.pixel(i)[c] = data[channels * i + c];
    if (channels == 3) image.pixel(i)[3] = 1.0f;
  }
  return image;
}

py::dict describe(const ColorConfig& config) {
  py::dict displays;
  for (const std::string& display : config.displays()) displays[py::str(display)] = config.views(display);
  py::dict result;
  result["config"] = config.description();
  result["working_space"] = config.working_space();
  result["default_display"] = config.default_display();
  result["displays"] = displays;
  result["looks"] = config.looks();
  result["color_spaces"] = config.color_spaces();
  return result;
}

}  // namespace

void bind_images(py::module_& module) {
  module.def(
      "write_exr",
      [](const std::filesystem::path& path, const py::object& image, bool half, bool keep_color_where_transparent) {
        ExrWriteOptions options;
        options.type = half ? ExrPixelType::half : ExrPixelType::float32;
        options.keep_color_where_transparent = keep_color_where_transparent;
        if (!py::isinstance<py::dict>(image)) return write_exr(image_from(image.cast<FloatArray>()), path, options);
        // Layers, as renderers write passes: each array's channels under <name>.R, .G, .B (and .A when it has 4).
        const py::dict named = image.cast<py::dict>();
        std::vector<Image> images;
        images.reserve(named.size());  // the layers point into it
        std::vector<ExrLayer> layers;
        for (const auto& [name, array] : named) {
          const FloatArray pixels = array.cast<FloatArray>();
          images.push_back(image_from(pixels));
          layers.push_back({name.cast<std::string>(), &images.back(), pixels.shape(2) == 4});
        }
        write_layered_exr(layers, path, options);
      },
      py::arg("path"), py::arg("image"), py::arg("half") = false, py::arg("keep_color_where_transparent") = false,
      "Writes an (H, W, 4) RGBA (or (H, W, 3) RGB) array as an EXR with channels R G B A, float32 or half, "
      "atomically (a temporary file, then a rename); or a dict of layer names to such arrays as one multilayer EXR "
      "(channels <name>.R, .G, .B, and .A for 4 channels), as a renderer writes its passes. Premultiplied, as "
      "OpenEXR's convention has it: RGB is written as 0 where alpha is 0 (the shader leaves the background colour "
      "there) unless keep_color_where_transparent.");
  module.def(
      "write_png",
      [](const std::filesystem::path& path, const FloatArray& image, double exposure, const std::string& view,
         const std::string& display, const std::string& look, std::array<double, 3> background, const std::string& ocio) {
        check_exposure(exposure);  // before the image is converted
        DisplaySettings settings{display, view, look, exposure, to_vec3(background)};
        write_png(image_from(image), path, DisplayTransform(color_config(ocio), settings));
      },
      py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0, py::arg("view") = "", py::arg("display") = "",
      py::arg("look") = "", py::arg("background") = std::array<double, 3>{0, 0, 0}, py::arg("ocio") = "",
      "Writes an 8-bit PNG, atomically: the image (premultiplied; colour where alpha is 0 is not drawn) over "
      "`background`, scaled by 2**exposure (a finite number of stops in [-40, 40]), through `look` and the `view` of `display` of the OCIO config `ocio` "
      "(as --ocio: a config file, 'blender', 'builtin'; default $OCIO, else built-in, whose views are 'reinhard' "
      "(default), 'aces' and 'clamp'). phongcl.colors() lists the names.");
  module.def(
      "colors", [](const std::string& ocio) { return describe(color_config(ocio)); }, py::arg("ocio") = "",
      "The OCIO config's displays (with their views), looks, colour spaces and working space, as a dict.");
  module.def(
      "read_exr",
      [](const std::filesystem::path& path, const std::string& layer) {
        Image image = read_exr(path, layer);
        py::array_t<float> out({image.height, image.width, 4});
        std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
        return out;
      },
      py::arg("path"), py::arg("layer") = "",
      "Reads R G B (and A, else 1) of an EXR as float32 (H, W, 4); with `layer`, <layer>.R, .G, .B (.A) of a "
      "multilayer EXR, such as a render's 'ViewLayer.Combined'.");
}

}  // namespace phongcl::python
