#include "raycast/depth_reconstruction.h"

#include <string>

#include "common/error.h"
#include "raycast/camera.h"

namespace phongcl {

void positions_from_depth(GBuffer& g, const Plane& depth, const Camera& camera, DepthConvention convention) {
  const PixelWindow& display = g.display_window;
  if (display.width() != camera.width || display.height() != camera.height)
    throw InputError(g.source, "display window is " + std::to_string(display.width()) + "x" +
                                   std::to_string(display.height()) + " but the scene camera is " +
                                   std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                                   ": positions from depth need the camera's image size");
  const PerspectiveCamera rays(camera);
  const glm::dvec3 forward = glm::normalize(camera.look_at - camera.eye);
  for (auto& plane : g.position) plane.assign(g.pixel_count(), 0.0f);
  for (int row = 0; row < g.height; ++row) {
    for (int column = 0; column < g.width; ++column) {
      const std::size_t i = static_cast<std::size_t>(row) * g.width + column;
      if (g.material[i] < 0.0f) continue;
      const Ray ray = rays.ray_through_pixel(g.data_window.x_min + column - display.x_min,
                                             g.data_window.y_min + row - display.y_min);
      const double t = convention == DepthConvention::distance ? depth[i] : depth[i] / glm::dot(ray.direction, forward);
      const glm::dvec3 p = ray.origin + t * ray.direction;
      for (int axis = 0; axis < 3; ++axis) g.position[axis][i] = static_cast<float>(p[axis]);
    }
  }
}

void positions_from_depth(GBufferRead& read, const Camera& camera) {
  positions_from_depth(read.gbuffer, read.depth, camera, read.depth_convention);
  if (read.edges_need_positions) repair_edges(read);
}

}  // namespace phongcl
