// 8-bit sRGB PNGs for looking at HDR results.
#include <png.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "image/image.h"

namespace phongcl {

void write_png(const Image& image, const std::filesystem::path& file, const DisplaySettings& display) {
  const std::vector<std::uint8_t> bytes = display_rgba8(image, display);

  // libpng's simplified API reports errors in png_image::message instead of longjmp-ing through
  // our destructors, and tags 8-bit non-linear output as sRGB.
  write_atomically(file, [&](const std::filesystem::path& temp) {
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGBA;
    if (!png_image_write_to_file(&png, temp.c_str(), 0, bytes.data(), 0, nullptr))
      throw InputError(file, std::string("cannot write PNG (") + png.message + ")");
  });
}

}  // namespace phongcl
