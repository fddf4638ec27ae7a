#include "shading/screen_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.h"
#include "shading/store3.h"

namespace phongcl {
namespace {

// Every this many shaded pixels one is projected back onto the image, to check the camera.
constexpr std::size_t kCheckEvery = 97;
constexpr double kMostPixelsOff = 1.5;

}  // namespace

ScreenDepth screen_depth(const Camera& camera, const GBuffer& gbuffer, int steps, float thickness) {
  const glm::dvec3 forward = glm::normalize(camera.look_at - camera.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  // As raycast/camera.h's rays: pixel (i, j) of the camera's image spans [i, i + 1) x [j, j + 1).
  const double scale = camera.height / (2.0 * std::tan(glm::radians(camera.fov_y_deg) / 2.0));
  const double centre_x = camera.width / 2.0 - (gbuffer.data_window.x_min - gbuffer.display_window.x_min);
  const double centre_y = camera.height / 2.0 - (gbuffer.data_window.y_min - gbuffer.display_window.y_min);

  ScreenDepth result;
  ScreenMarch& march = result.march;
  store3(march.forward, forward);
  store3(march.right, right);
  store3(march.up, up);
  march.scale_x = march.scale_y = static_cast<float>(scale);
  march.centre_x = static_cast<float>(centre_x);
  march.centre_y = static_cast<float>(centre_y);
  march.width = static_cast<unsigned>(gbuffer.width);
  march.height = static_cast<unsigned>(gbuffer.height);
  march.steps = static_cast<unsigned>(steps);
  march.thickness = thickness;

  result.depth.assign(gbuffer.pixel_count(), std::numeric_limits<float>::infinity());
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0, worst_off = 0.0;
  std::size_t shaded = 0, worst = 0;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
    const glm::dvec3 p = glm::dvec3(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]) - camera.eye;
    const double z = glm::dot(p, forward);
    result.depth[i] = static_cast<float>(z);
    nearest = std::min(nearest, z);
    farthest = std::max(farthest, z);
    if (shaded++ % kCheckEvery != 0) continue;
    const double x = centre_x + scale * glm::dot(p, right) / z, y = centre_y - scale * glm::dot(p, up) / z;
    const double column = static_cast<double>(i % gbuffer.width) + 0.5, row = static_cast<double>(i / gbuffer.width) + 0.5;
    const double off = z > 0.0 ? std::max(std::abs(x - column), std::abs(y - row)) : INFINITY;
    if (off > worst_off) worst_off = off, worst = i;
  }
  if (shaded == 0) throw InputError(gbuffer.source, "no shaded pixel: screen-space shadows have nothing to march over");
  if (!(worst_off <= kMostPixelsOff))
    throw InputError(gbuffer.source,
                     "the camera does not project the G-buffer's positions onto their pixels (pixel (" +
                         std::to_string(worst % gbuffer.width) + ", " + std::to_string(worst / gbuffer.width) +
                         ") lands " + std::to_string(worst_off) +
                         " pixels away): screen-space shadows need the camera that rendered it");
  // Surfaces nearer than the eye's own depth could not be drawn; a march below the nearest one
  // would divide by nothing.
  march.near_depth = static_cast<float>(std::max(nearest * 0.5, 1e-6 * farthest));
  march.far_depth = static_cast<float>(farthest);
  return result;
}

}  // namespace phongcl
