#include <cstddef>

#include "common/error.h"
#include "raycast/camera.h"
#include "raycast/geometry.h"
#include "raycast/raycast.h"

namespace phongcl {
namespace {

// Primary rays start at the eye, so this only drops surfaces passing through the eye itself.
constexpr double kMinHitDistance = 1e-9;

GBuffer empty_gbuffer(int width, int height) {
  GBuffer gbuffer;
  gbuffer.width = width;
  gbuffer.height = height;
  gbuffer.data_window = {0, 0, width - 1, height - 1};
  gbuffer.display_window = gbuffer.data_window;
  for (int axis = 0; axis < 3; ++axis) {
    gbuffer.position[axis].assign(gbuffer.pixel_count(), 0.0f);
    gbuffer.normal[axis].assign(gbuffer.pixel_count(), 0.0f);
  }
  gbuffer.material.assign(gbuffer.pixel_count(), -1.0f);
  return gbuffer;
}

void cast_pixel(const PerspectiveCamera& camera, const SceneGeometry& geometry, int x, int y, GBuffer& gbuffer) {
  const Ray ray = camera.ray_through_pixel(x, y);
  const std::optional<SurfaceHit> hit = geometry.nearest_hit(ray, kMinHitDistance);
  if (!hit) return;
  const glm::dvec3 position = ray.origin + hit->t * ray.direction;
  // Shading wants the side the viewer sees: a normal pointing back along the ray.
  const glm::dvec3 normal = glm::dot(hit->normal, ray.direction) > 0.0 ? -hit->normal : hit->normal;
  const std::size_t index = static_cast<std::size_t>(y) * gbuffer.width + x;
  for (int axis = 0; axis < 3; ++axis) {
    gbuffer.position[axis][index] = static_cast<float>(position[axis]);
    gbuffer.normal[axis][index] = static_cast<float>(normal[axis]);
  }
  gbuffer.material[index] = static_cast<float>(hit->material);
}

}  // namespace

GBuffer generate_gbuffer(const Scene& scene) {
  if (!scene.has_camera) throw InputError(scene.source, "no \"camera\": the G-buffer generator needs one");
  const PerspectiveCamera camera(scene.camera);
  const SceneGeometry geometry(scene.objects);
  GBuffer gbuffer = empty_gbuffer(scene.camera.width, scene.camera.height);
  for (int y = 0; y < gbuffer.height; ++y)
    for (int x = 0; x < gbuffer.width; ++x) cast_pixel(camera, geometry, x, y, gbuffer);
  return gbuffer;
}

}  // namespace phongcl
