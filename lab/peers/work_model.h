#pragma once
// How much work shading a pixel is, for roofline bounds: bytes that must cross the memory bus and
// floating-point operations the formula needs. One model for every implementation (the formula's
// work, not each one's instruction count), so a variant that executes more instructions for the
// same work shows a lower fraction of its bound.
namespace phongcl {

// Bytes per pixel: compulsory traffic, each input the formula needs read once and the output
// written once; uniform tables stay in cache and write-allocate reads are not counted (the STREAM
// convention, as for the measured bandwidth). Material index (4) + RGBA float out (16), and with
// any light P and N (float 24, half 12); without lights L_o = ka La needs neither.
inline double bytes_per_pixel(bool half_planes, int lights) {
  const double geometry = lights > 0 ? 6.0 * (half_planes ? 2 : 4) : 0.0;
  return geometry + 4 + 16;
}

// Flops counted on the peers' code (peers/phong_pixel.h, peers/float_math.h): add, subtract,
// multiply, min/max, compare, select, convert, divide and square root = 1, FMA = 2.
//   unit_or_zero: max 2, scale 3, dot 5, compare 1, sqrt 1, divide 1, select 1, scale 3   = 17
//   log_positive: 22 (reduction, selects, divide) + series 4 FMA = 8                      = 30
//   exp_float: clamp 2, round 3, Cody-Waite 2 FMA = 4, series 7 FMA = 14, scale 2, select 1 = 26
//   light_term: n.l 5, compare 1, r 7, v - r 3, v.r 5, |v-r|^2/2 6, q ln 1, log 30, exp 26,
//               selects 5                                                                  = 89
//   accumulate: 6 FMA                                                                       = 12
inline constexpr double kFlopsPerDirectionalLight = 89 + 12;
inline constexpr double kFlopsPerPointLight = 3 + 17 + kFlopsPerDirectionalLight;  // l = unit(L - P)
//   per pixel: -P 3, n and v 2 x 17, ka La + kd D + ks S 3 x 2 FMA = 12; without lights ka La = 3
inline constexpr double kFlopsPerLitPixel = 3 + 2 * 17 + 12;
inline constexpr double kFlopsPerUnlitPixel = 3;

inline double flops_per_pixel(int point_lights, int directional_lights) {
  if (point_lights + directional_lights == 0) return kFlopsPerUnlitPixel;
  return kFlopsPerLitPixel + point_lights * kFlopsPerPointLight + directional_lights * kFlopsPerDirectionalLight;
}

// Pixels per second that the machine's bandwidth and FMA peak allow for this much work per pixel.
inline double roofline_pixels_per_second(double bandwidth_bytes_per_s, double peak_flops_per_s, double bytes_per_pixel,
                                         double flops_per_pixel) {
  const double memory_bound = bandwidth_bytes_per_s / bytes_per_pixel;
  const double compute_bound = peak_flops_per_s / flops_per_pixel;
  return memory_bound < compute_bound ? memory_bound : compute_bound;
}

}  // namespace phongcl
