#include "stability/exact_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phongcl {

double relative_error(float value, long double exact, double abs_floor) {
  constexpr double kInfinite = std::numeric_limits<double>::infinity();
  if (std::isnan(value)) return kInfinite;
  const float exact_in_float = static_cast<float>(exact);  // round to nearest: +Inf iff it overflows float
  if (std::isinf(exact_in_float) || std::isinf(value)) return value == exact_in_float ? 0.0 : kInfinite;
  const long double scale = std::max(std::fabs(exact), static_cast<long double>(abs_floor));
  return static_cast<double>(std::fabs(static_cast<long double>(value) - exact) / scale);
}

double relative_error_to_any(float value, const std::vector<long double>& admissible, bool span, double abs_floor) {
  double error = std::numeric_limits<double>::infinity();
  for (long double exact : admissible) error = std::min(error, relative_error(value, exact, abs_floor));
  if (span && std::isfinite(value) && !admissible.empty()) {
    const auto [lo, hi] = std::minmax_element(admissible.begin(), admissible.end());
    if (*lo <= value && value <= *hi) return 0.0;
  }
  return error;
}

ExactComparison compare_with_exact(const Image& image, const Scene& scene, const GBuffer& gbuffer, double abs_floor) {
  ExactComparison result;
  bool any_shaded = false;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    const float* pixel = image.pixel(i);
    for (int c = 0; c < 4; ++c) result.nan_values += std::isnan(pixel[c]);
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) {
      bool exact_background = pixel[3] == 0.0f;
      for (int c = 0; c < 3; ++c) exact_background = exact_background && pixel[c] == static_cast<float>(scene.background[c]);
      result.background_mismatches += !exact_background;
      continue;
    }
    const ExactColor exact = exact_shade_pixel(scene, gbuffer, i);
    for (int c = 0; c < 3; ++c) {
      const double error = relative_error(pixel[c], exact[c], abs_floor);
      if (error > result.max_rel || !any_shaded) {
        any_shaded = true;
        result.max_rel = error;
        result.worst_pixel = i;
        result.worst_channel = c;
        result.worst_value = pixel[c];
        result.worst_exact = exact[c];
      }
    }
  }
  return result;
}

}  // namespace phongcl
