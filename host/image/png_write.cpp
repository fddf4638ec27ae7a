// 8-bit sRGB PNGs for looking at HDR results.
#include <png.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "image/image.h"

namespace phongcl {

std::string encode_png(const std::vector<std::uint8_t>& rgba, int width, int height) {
  // libpng's simplified API reports errors in png_image::message instead of longjmp-ing through
  // our destructors, and tags 8-bit non-linear output as sRGB.
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(width);
  png.height = static_cast<png_uint_32>(height);
  png.format = PNG_FORMAT_RGBA;
  png.flags = PNG_IMAGE_FLAG_FAST;
  // Into a buffer of the largest size the image can take: asking for the size first would
  // compress twice.
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, rgba.data(), 0, nullptr))
    throw std::runtime_error(png.message);
  bytes.resize(size);
  return bytes;
}

void write_png(const Image& image, const std::filesystem::path& file, const DisplaySettings& display) {
  check_exposure(display.exposure_stops);
  std::string bytes;
  try {
    bytes = encode_png(display_rgba8(image, display), image.width, image.height);
  } catch (const std::runtime_error& error) {
    throw InputError(file, std::string("cannot write PNG (") + error.what() + ")");
  }
  write_atomically(file, [&](const std::filesystem::path& temp) {
    std::ofstream stream(temp, std::ios::binary);
    stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    stream.close();
    if (!stream) throw InputError(temp, std::string("cannot write PNG: ") + std::strerror(errno));
  });
}

}  // namespace phongcl
