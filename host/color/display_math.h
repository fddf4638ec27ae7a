#pragma once
// The two per-value steps of a display transform in scalar code, shared by the scalar loops
// (color/pixel_kernels_scalar.cpp), the checks of the compiled tables (color/view_pipeline.cpp)
// and the exact byte tables (color/byte_steps.h), so that all three compute the same bytes.
// Not included by the AVX2 loops: inline functions compiled there could stand in for these.
#include <bit>
#include <cstdint>

namespace phongcl {

// A per-channel table indexed by the float's top 16 bits (sign, exponent, 7 mantissa bits),
// linear in the low 16 (within one bucket a float's value is linear in its low bits).
inline constexpr int kTableShift = 16;
inline float table_lookup(const float* table, float x) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  const float* cell = table + (bits >> kTableShift);
  return cell[0] + (cell[1] - cell[0]) * (static_cast<float>(bits & 0xffffu) * (1.0f / 65536.0f));
}

// A display value as a byte: round half up (as Blender writes bytes), clamped; NaN is 0.
inline std::uint8_t display_byte(float v) {
  const float t = v * 255.0f + 0.5f;
  return static_cast<std::uint8_t>(t > 0.0f ? (t < 255.0f ? t : 255.0f) : 0.0f);
}

}  // namespace phongcl
