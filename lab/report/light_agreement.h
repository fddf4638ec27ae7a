#pragma once
// How often an image's light agrees with a renderer's, pixel by pixel: per light, the shaded value
// must be within `tolerance` times that light's unshadowed value of the renderer's (for shadows:
// Cycles' direct diffuse light, DiffDir x DiffCol, of each light rendered alone). Pixels next to a
// silhouette (another object or the sky within one pixel) are left out: there a pixel's sample
// and its neighbours see different surfaces.
#include <array>
#include <cstddef>
#include <vector>

namespace phongcl {

// One light's RGB planes, width x height floats each.
struct LightImages {
  std::array<std::vector<float>, 3> expected, shaded, unshadowed;
};

struct LightAgreement {
  std::size_t pixels = 0;                        // away from silhouettes
  std::size_t agreeing = 0;                      // every light agrees there
  std::vector<std::size_t> agreeing_per_light;
  int worst_x = -1, worst_y = -1;                // the largest miss, in units of the allowance
  double worst_miss = 0.0;
  double fraction() const { return pixels ? static_cast<double>(agreeing) / static_cast<double>(pixels) : 0.0; }
};

// Pixels whose 3x3 neighbourhood is one object (`object`: per-pixel object index) and no sky
// (`depth` not finite or at least 1e9: Cycles writes 1e10 where a ray missed).
std::vector<bool> away_from_silhouettes(const std::vector<float>& object, const std::vector<float>& depth, int width,
                                        int height);

// How closely one light's shaded values follow the renderer's where the renderer lights the pixel:
// per pixel, the largest channel's |shaded - expected| over the largest expected channel, over the
// pixels of `mask` whose largest expected channel exceeds `floor` times the brightest one's (the
// rest, outside a spot's cone or at grazing light, have no meaningful relative error).
struct RelativeErrors {
  std::size_t pixels = 0;
  double median = 0.0, p99 = 0.0;
};
RelativeErrors relative_errors(const LightImages& light, const std::vector<bool>& mask, double floor = 1e-3);

// Throws std::invalid_argument when the planes' sizes differ from the mask's.
LightAgreement light_agreement(const std::vector<LightImages>& lights, const std::vector<bool>& mask, int width,
                               double tolerance);

}  // namespace phongcl
