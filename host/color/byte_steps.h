#pragma once
// A monotone function from floats to bytes as the floats where it steps up: the display transform
// of a view that is one curve per channel (the built-in views, Blender's Standard), exposure
// folded in, costs a table lookup and a compare per channel, with the same bytes as the curve.
// Positive floats order as their bit patterns do: steps_[k] is the pattern of the first value whose
// byte exceeds k, coarse_[p >> 16] the byte at the start of each bucket of patterns.
#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace phongcl {

class ByteSteps {
 public:
  // `byte_of` must be non-decreasing over [0, +Inf]; negative values and NaN are given its byte at
  // 0. Empty when two steps fall in one bucket (a curve steeper than this table resolves).
  static std::optional<ByteSteps> make(const std::function<std::uint8_t(float)>& byte_of);

  std::uint8_t operator()(float value) const {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
    bits = bits > kInfinityBits ? 0 : bits;  // NaN or negative: as 0
    const int byte = coarse_[bits >> kCoarseShift];
    return static_cast<std::uint8_t>(byte + (bits >= steps_[byte] ? 1 : 0));
  }

 private:
  static constexpr std::uint32_t kInfinityBits = 0x7f800000u;  // above it: NaN; sign bit set: negative
  static constexpr int kCoarseShift = 16;
  ByteSteps() : coarse_((kInfinityBits >> kCoarseShift) + 1) {}
  std::array<std::uint32_t, 256> steps_{};
  std::vector<std::uint8_t> coarse_;
};

}  // namespace phongcl
