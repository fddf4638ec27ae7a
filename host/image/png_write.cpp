// 8-bit sRGB PNGs for looking at HDR results.
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "image/image.h"

namespace phongcl {

namespace {

double tone_map(double x, ToneMap tone_map) {
  switch (tone_map) {
    case ToneMap::clamp: return std::min(x, 1.0);
    case ToneMap::reinhard: return x / (1.0 + x);
    case ToneMap::aces:  // Narkowicz 2015 fit of the ACES filmic curve
      return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  }
  return x;
}

// The exact sRGB transfer function (piecewise), not a 2.2 power.
double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::uint8_t to_byte(double unit) { return static_cast<std::uint8_t>(std::lround(std::clamp(unit, 0.0, 1.0) * 255.0)); }

std::uint8_t display_color(float value, double scale, ToneMap map) {
  const double x = value * scale;
  if (std::isnan(x) || x <= 0.0) return 0;
  if (std::isinf(x)) return 255;  // the tone curves give inf/inf = NaN there; the limit is white
  return to_byte(srgb_encode(tone_map(x, map)));
}

std::uint8_t display_alpha(float alpha) { return std::isnan(alpha) ? 0 : to_byte(alpha); }

}  // namespace

void write_png(const Image& image, const std::filesystem::path& file, const DisplaySettings& display) {
  const double scale = std::exp2(display.exposure_stops);
  std::vector<std::uint8_t> bytes(4 * image.pixel_count());
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const float* in = image.pixel(i);
    for (int c = 0; c < 3; ++c) bytes[4 * i + c] = display_color(in[c], scale, display.tone_map);
    bytes[4 * i + 3] = display_alpha(in[3]);
  }

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
