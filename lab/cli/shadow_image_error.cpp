#include "cli/shadow_image_error.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace phongcl::cli {

ShadowImageError shadow_image_error(const Image& image, const Image& reference, const Image& unshadowed,
                                    const GBuffer& gbuffer, double tolerance) {
  std::size_t shaded = 0, beyond = 0;
  double error = 0.0;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
    ++shaded;
    double largest = 0.0, reach = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double miss = std::abs(static_cast<double>(image.pixel(i)[c]) - reference.pixel(i)[c]);
      largest = std::max(largest, miss);
      reach = std::max(reach, static_cast<double>(unshadowed.pixel(i)[c]));
      error += miss;
    }
    beyond += largest > tolerance * reach;
  }
  const double count = static_cast<double>(std::max<std::size_t>(shaded, 1));
  return {static_cast<double>(beyond) / count, error / (3.0 * count)};
}

}  // namespace phongcl::cli
