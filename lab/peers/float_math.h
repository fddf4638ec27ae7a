#pragma once
// Float ln and exp for the peers' specular power x^q = exp(q ln x), as straight-line code (bit
// operations, polynomials, selects) that GCC vectorises under `omp simd`. glibc's vector expf/logf
// (libmvec) are only declared to GCC under -ffast-math, which would also drop the NaN/degenerate
// handling; these stay IEEE and are accurate to a few float ulps (tests/test_peers.cpp measures them).
#include <bit>
#include <cmath>
#include <cstdint>

namespace phongcl::peer_math {

inline constexpr float kLn2High = 0.693145751953125f;     // ln 2 split so k * kLn2High is exact
inline constexpr float kLn2Low = 1.42860677e-06f;         // for |k| < 2^9
inline constexpr float kSmallestNormal = 1.17549435e-38f;

// ln(x) for x > 0. `one_minus_x` is 1 - x computed by the caller without cancellation: near
// x = 1 the rounding of x itself would be multiplied by q in x^q, so there the series runs on it.
inline float log_positive(float x, float one_minus_x) {
  // x = 2^e * f with f in [sqrt(1/2), sqrt(2)); ln x = e ln 2 + 2 atanh(s), s = (f - 1) / (f + 1).
  const bool subnormal = x < kSmallestNormal;
  const std::int32_t bits = std::bit_cast<std::int32_t>(subnormal ? x * 8388608.0f : x);  // * 2^23
  std::int32_t e = (bits >> 23) - (subnormal ? 127 + 23 : 127);
  float f = std::bit_cast<float>((bits & 0x007fffff) | 0x3f800000);  // [1, 2)
  const bool high = f > 1.41421356f;
  f = high ? f * 0.5f : f;
  e = high ? e + 1 : e;
  // Within 0.29 of 1 the reduction is the identity (e = 0, f = x): use 1 - x as given instead.
  const bool near_one = std::fabs(one_minus_x) < 0.29f;
  const float numerator = near_one ? -one_minus_x : f - 1.0f;  // f - 1 is exact (Sterbenz)
  const float denominator = near_one ? 2.0f - one_minus_x : f + 1.0f;
  const float exponent = near_one ? 0.0f : static_cast<float>(e);
  const float s = numerator / denominator;  // |s| <= 0.172, so five terms reach 2e-9
  const float s2 = s * s;
  const float atanh_series = s * (2.0f + s2 * (2.0f / 3 + s2 * (2.0f / 5 + s2 * (2.0f / 7 + s2 * (2.0f / 9)))));
  return exponent * kLn2High + (exponent * kLn2Low + atanh_series);
}

// 2^k for integer k in [-126, 127], built from the exponent bits (a normal float).
inline float power_of_two(std::int32_t k) { return std::bit_cast<float>((k + 127) << 23); }

// e^y for y <= 88; 0 where e^y is below float's smallest normal, 2^-126 (e^-87.34): as in the
// kernel, since each operation on a subnormal takes a microcode assist on x86.
inline constexpr float kLnSmallestNormal = -87.3365448f;
inline float exp_float(float y) {
  const float clamped = y < kLnSmallestNormal ? kLnSmallestNormal : y;
  const float k = std::floor(clamped * 1.44269504f + 0.5f);  // nearest integer to y / ln 2
  const float r = (clamped - k * kLn2High) - k * kLn2Low;    // |r| <= ln2 / 2, Cody-Waite
  // Taylor series of e^r to r^7: truncation below 1e-8 relative on |r| <= 0.347.
  const float p =
      1.0f + r * (1.0f + r * (1.0f / 2 + r * (1.0f / 6 + r * (1.0f / 24 + r * (1.0f / 120 + r * (1.0f / 720 + r * (1.0f / 5040)))))));
  const float scaled = p * power_of_two(static_cast<std::int32_t>(k));  // k >= -126
  return y < kLnSmallestNormal ? 0.0f : scaled;
}

}  // namespace phongcl::peer_math
