#pragma once
// How far a shaded image is from the long double oracle, value by value.
#include <cstddef>
#include <vector>

#include "image/image.h"
#include "stability/exact_shade.h"

namespace phongcl {

// |value - exact| / max(|exact|, abs_floor). Where the exact value rounds to +-Inf in float, the
// value must be that infinity (error 0) and anything else is an infinite error; a NaN value is an
// infinite error whatever the exact value. So overflow counts as right only where it is exact.
double relative_error(float value, long double exact, double abs_floor);

// relative_error against the nearest of several admissible exact values; with `span`, 0 anywhere
// between the smallest and the largest of them.
double relative_error_to_any(float value, const std::vector<long double>& admissible, bool span, double abs_floor);

struct ExactComparison {
  double max_rel = 0.0;
  std::size_t worst_pixel = 0;
  int worst_channel = 0;
  float worst_value = 0.0f;
  long double worst_exact = 0;
  std::size_t nan_values = 0;          // NaN anywhere in RGBA
  std::size_t background_mismatches = 0;  // unshaded pixels not exactly background with alpha 0
};

// Every pixel of `image` against exact_shade_pixel: shaded pixels by relative_error on R, G, B;
// unshaded ones must hold the background colour exactly with alpha 0.
ExactComparison compare_with_exact(const Image& image, const Scene& scene, const GBuffer& gbuffer, double abs_floor);

}  // namespace phongcl
