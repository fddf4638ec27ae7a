// Images as NumPy arrays (H, W, 4) float32, RGBA: to and from EXR, to PNG.
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "image/image.h"

namespace phongcl::python {

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

ToneMap parse_tone_map(const std::string& name) {
  if (name == "clamp") return ToneMap::clamp;
  if (name == "reinhard") return ToneMap::reinhard;
  if (name == "aces") return ToneMap::aces;
  throw py::value_error("tonemap must be 'clamp', 'reinhard' or 'aces', not '" + name + "'");
}

}  // namespace

void bind_images(py::module_& module) {
  module.def(
      "write_exr",
      [](const std::filesystem::path& path, const FloatArray& image, bool half) {
        write_exr(path, image_from(image), half ? ExrPixelType::half : ExrPixelType::float32);
      },
      py::arg("path"), py::arg("image"), py::arg("half") = false,
      "Writes an (H, W, 4) RGBA (or (H, W, 3) RGB) array as an EXR with channels R G B A, float32 or "
      "half, atomically (a temporary file, then a rename).");
  module.def(
      "write_png",
      [](const std::filesystem::path& path, const FloatArray& image, double exposure, const std::string& tonemap) {
        check_exposure(exposure);  // before the image is converted
        write_png(path, image_from(image), DisplaySettings{exposure, parse_tone_map(tonemap)});
      },
      py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0, py::arg("tonemap") = "reinhard",
      "Writes an 8-bit sRGB PNG: scaled by 2**exposure (a finite number of stops in [-40, 40]), tone mapped "
      "('clamp', 'reinhard', 'aces'), atomically.");
  module.def(
      "read_exr",
      [](const std::filesystem::path& path) {
        Image image = read_exr(path);
        py::array_t<float> out({image.height, image.width, 4});
        std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
        return out;
      },
      py::arg("path"), "Reads R G B (and A, else 1) of an EXR as float32 (H, W, 4).");
}

}  // namespace phongcl::python
