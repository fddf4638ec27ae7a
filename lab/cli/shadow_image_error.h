#pragma once
// How far a shadowed image is from a reference one (exact or converged shadows), for the shadow
// benches: the share of shaded pixels whose largest channel misses by more than `tolerance` times
// the unshadowed pixel's largest channel, and the mean absolute error over R, G, B.
#include "gbuffer/gbuffer.h"
#include "image/image.h"

namespace phongcl::cli {

struct ShadowImageError {
  double beyond = 0.0;          // fraction of shaded pixels missing by more than the tolerance
  double mean_abs_error = 0.0;  // over shaded pixels and R, G, B
};

ShadowImageError shadow_image_error(const Image& image, const Image& reference, const Image& unshadowed,
                                    const GBuffer& gbuffer, double tolerance);

}  // namespace phongcl::cli
