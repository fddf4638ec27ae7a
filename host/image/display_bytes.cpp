// HDR to 8-bit display values: exposure, tone map, sRGB. A table over the tone-mapped value makes
// it a few nanoseconds a channel (the server encodes every frame of a drag) and exact: each table
// cell holds the byte at its start and the first value where the byte steps up, found by bisection
// on the exact formula, so every output equals lround(255 * srgb(tone_map(x))).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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

std::uint8_t exact_srgb_byte(double mapped) { return to_byte(srgb_encode(mapped)); }

// sRGB's steepest slope is 12.92 * 255 = 3295 bytes per unit at 0: with 8192 cells a cell holds
// at most one step (0.4 on average there, fewer elsewhere).
class SrgbTable {
 public:
  static constexpr int kCells = 8192;
  SrgbTable() {
    for (int i = 0; i < kCells; ++i) {
      const double start = double(i) / kCells, end = double(i + 1) / kCells;
      base_[i] = exact_srgb_byte(start);
      step_[i] = std::numeric_limits<double>::infinity();
      if (exact_srgb_byte(std::nextafter(end, 0.0)) == base_[i]) continue;
      double below = start, above = end;  // byte(below) == base, byte(above) > base
      while (std::nextafter(below, 1.0) < above) {
        const double middle = below + (above - below) / 2;
        (exact_srgb_byte(middle) == base_[i] ? below : above) = middle;
      }
      step_[i] = above;
    }
  }
  std::uint8_t byte(double mapped) const {  // mapped in [0, 1]
    const int cell = std::min(static_cast<int>(mapped * kCells), kCells - 1);
    return static_cast<std::uint8_t>(base_[cell] + (mapped >= step_[cell] ? 1 : 0));
  }

 private:
  std::array<std::uint8_t, kCells> base_{};
  std::array<double, kCells> step_{};
};

std::uint8_t display_color(const SrgbTable& table, float value, double scale, ToneMap map) {
  const double x = value * scale;
  if (std::isnan(x) || x <= 0.0) return 0;
  if (std::isinf(x)) return 255;  // the tone curves give inf/inf = NaN there; the limit is white
  return table.byte(std::clamp(tone_map(x, map), 0.0, 1.0));
}

std::uint8_t display_alpha(float alpha) { return std::isnan(alpha) ? 0 : to_byte(alpha); }

}  // namespace

void display_rgba8(const Image& image, const DisplaySettings& display, std::size_t first_row, std::size_t rows,
                   std::uint8_t* out) {
  static const SrgbTable table;
  const double scale = std::exp2(display.exposure_stops);
  const std::size_t first = first_row * image.width, count = rows * image.width;
  for (std::size_t i = first; i < first + count; ++i) {
    const float* in = image.pixel(i);
    std::uint8_t* bytes = out + 4 * i;
    for (int c = 0; c < 3; ++c) bytes[c] = display_color(table, in[c], scale, display.tone_map);
    bytes[3] = display_alpha(in[3]);
  }
}

std::vector<std::uint8_t> display_rgba8(const Image& image, const DisplaySettings& display) {
  std::vector<std::uint8_t> bytes(4 * image.pixel_count());
  display_rgba8(image, display, 0, image.height, bytes.data());
  return bytes;
}

}  // namespace phongcl
