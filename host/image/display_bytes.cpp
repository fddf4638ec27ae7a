// HDR to 8-bit display values: exposure, tone map, sRGB, every output equal to
// lround(255 * srgb(tone_map(x))). A table over the tone-mapped value makes the exact function
// cheap (each cell holds the byte at its start and the first value where the byte steps up, found by
// bisection on the formula); DisplayEncoder bisects that function once more, over the input floats,
// so that a frame's channels (the server encodes every frame of a drag) need no arithmetic at all.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "image/display_encoder.h"
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

// lround(255 * clamp(alpha)): the product of a float and 255 is exact in a double, so adding a
// half and truncating rounds exactly as lround does.
std::uint8_t display_alpha(float alpha) {
  return std::isnan(alpha) ? 0 : static_cast<std::uint8_t>(std::clamp(double(alpha), 0.0, 1.0) * 255.0 + 0.5);
}

const SrgbTable& srgb_table() {
  static const SrgbTable table;
  return table;
}

constexpr std::uint32_t kInfinityBits = 0x7f800000u;  // above it: NaN; sign bit set: negative
constexpr int kCoarseShift = 16;

}  // namespace

DisplayEncoder::DisplayEncoder(const DisplaySettings& display) : coarse_((kInfinityBits >> kCoarseShift) + 1) {
  const SrgbTable& table = srgb_table();
  const double scale = std::exp2(display.exposure_stops);
  const auto exact = [&](std::uint32_t bits) {
    return display_color(table, std::bit_cast<float>(bits), scale, display.tone_map);
  };
  for (int k = 0; k < 255; ++k) {  // exact(0) == 0 <= k < 255 == exact(+Inf)
    std::uint32_t below = 0, above = kInfinityBits;
    while (above - below > 1) {
      const std::uint32_t middle = below + (above - below) / 2;
      (exact(middle) > k ? above : below) = middle;
    }
    steps_[k] = above;
  }
  steps_[255] = std::numeric_limits<std::uint32_t>::max();  // no byte above 255
  // A bucket spans a factor of at most 1 + 2^-7 (ln: 0.0078) and the steepest curve (clamp, near
  // 1) climbs 112 bytes per unit of ln x, so steps are at least 0.0089 apart: one per bucket at most.
  for (int k = 0; k + 1 < 255; ++k)
    if (steps_[k] >> kCoarseShift == steps_[k + 1] >> kCoarseShift)
      throw std::logic_error("DisplayEncoder: two byte steps in one table bucket");
  int byte = 0;
  for (std::size_t bucket = 0; bucket < coarse_.size(); ++bucket) {
    while (byte < 255 && steps_[byte] <= (bucket << kCoarseShift)) ++byte;
    coarse_[bucket] = static_cast<std::uint8_t>(byte);
  }
}

void DisplayEncoder::encode_rows(const Image& image, std::size_t first_row, std::size_t rows, std::uint8_t* out) const {
  const std::uint8_t* coarse = coarse_.data();
  const std::uint32_t* steps = steps_.data();
  const auto color_byte = [&](float value) {  // branch-free: values are not predictable
    std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
    bits = bits > kInfinityBits ? 0 : bits;  // NaN or negative: as 0
    const int byte = coarse[bits >> kCoarseShift];
    return static_cast<std::uint8_t>(byte + (bits >= steps[byte] ? 1 : 0));
  };
  const std::size_t first = first_row * image.width, count = rows * image.width;
  for (std::size_t i = first; i < first + count; ++i) {
    const float* in = image.pixel(i);
    std::uint8_t* bytes = out + 4 * i;
    for (int c = 0; c < 3; ++c) bytes[c] = color_byte(in[c]);
    bytes[3] = display_alpha(in[3]);
  }
}

std::vector<std::uint8_t> display_rgba8(const Image& image, const DisplaySettings& display) {
  std::vector<std::uint8_t> bytes(4 * image.pixel_count());
  DisplayEncoder(display).encode_rows(image, 0, image.height, bytes.data());
  return bytes;
}

}  // namespace phongcl
