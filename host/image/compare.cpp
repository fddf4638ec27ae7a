// Error metrics between a test image and an expected one.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "image/image.h"

namespace phongcl {

namespace {

// Values that cannot enter the error arithmetic. Equal infinities are a match; anything else
// involving NaN or infinity is a mismatch.
enum class Nonfinite { none, match, mismatch };

Nonfinite classify(double t, double e) {
  if (std::isfinite(t) && std::isfinite(e)) return Nonfinite::none;
  if (std::isinf(t) && std::isinf(e) && (t > 0) == (e > 0)) return Nonfinite::match;
  return Nonfinite::mismatch;
}

}  // namespace

ErrorStats compare_images(const Image& test, const Image& expected, double abs_floor,
                          const std::vector<bool>& mask) {
  if (test.width != expected.width || test.height != expected.height)
    throw std::invalid_argument("compare_images: test is " + std::to_string(test.width) + "x" +
                                std::to_string(test.height) + ", expected is " +
                                std::to_string(expected.width) + "x" + std::to_string(expected.height));
  if (!mask.empty() && mask.size() != expected.pixel_count())
    throw std::invalid_argument("compare_images: mask has " + std::to_string(mask.size()) +
                                " entries for " + std::to_string(expected.pixel_count()) + " pixels");

  ErrorStats stats;
  double sum_squared = 0.0, peak = 0.0;
  std::size_t values = 0;
  bool have_worst = false;
  for (std::size_t i = 0; i < expected.pixel_count(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++stats.pixels_compared;
    for (int c = 0; c < 3; ++c) {
      const double t = test.pixel(i)[c], e = expected.pixel(i)[c];
      const Nonfinite nonfinite = classify(t, e);
      if (nonfinite == Nonfinite::mismatch) ++stats.nonfinite_mismatches;  // counted per channel value
      if (nonfinite != Nonfinite::none) continue;

      const double abs_error = std::abs(t - e);
      const double rel_error = abs_error / std::max(std::abs(e), abs_floor);
      sum_squared += abs_error * abs_error;
      ++values;
      peak = std::max(peak, std::abs(e));
      stats.max_abs = std::max(stats.max_abs, abs_error);
      if (!have_worst || rel_error > stats.max_rel) {
        have_worst = true;
        stats.max_rel = rel_error;
        stats.worst_pixel = i;
        stats.worst_channel = c;
        stats.worst_test = t;
        stats.worst_expected = e;
      }
    }
  }
  // Coordinates as the file states them (the data window may not start at 0, 0).
  const auto width = static_cast<std::size_t>(expected.width > 0 ? expected.width : 1);
  stats.worst_x = expected.data_window.x_min + static_cast<int>(stats.worst_pixel % width);
  stats.worst_y = expected.data_window.y_min + static_cast<int>(stats.worst_pixel / width);
  stats.rmse = values > 0 ? std::sqrt(sum_squared / static_cast<double>(values)) : 0.0;
  stats.psnr_db = stats.rmse == 0.0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(peak / stats.rmse);
  return stats;
}

}  // namespace phongcl
