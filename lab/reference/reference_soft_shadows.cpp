#include "reference/reference_soft_shadows.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "reference/reference_shadows.h"

namespace phongcl {

double reference_area_visibility(const SceneShapes& shapes, const AreaLight& light, const SurfacePoint& point,
                                 const glm::dvec3& eye, double offset_scale, int grid,
                                 const std::function<double(const glm::dvec3& emitter_point)>& cone) {
  const glm::dvec3 normal = glm::normalize(light.direction);
  // The emitter's frame, written here from docs/shading.md: v along up made orthogonal to the normal
  // (any such for a disk), u completing it; a disk's diameter is size.x.
  const glm::dvec3 up = light.shape == AreaShape::rect ? light.up : (std::abs(normal.x) < 0.5 ? glm::dvec3(1, 0, 0)
                                                                                               : glm::dvec3(0, 1, 0));
  const glm::dvec3 v = glm::normalize(up - glm::dot(up, normal) * normal);
  const glm::dvec3 u = glm::cross(v, normal);
  const double half_u = light.size.x / 2.0, half_v = (light.shape == AreaShape::rect ? light.size.y : light.size.x) / 2.0;
  const glm::dvec3 n = glm::normalize(point.normal);
  double seen = 0.0, total = 0.0;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      const double s = 2.0 * (i + 0.5) / grid - 1.0, t = 2.0 * (j + 0.5) / grid - 1.0;
      if (light.shape == AreaShape::disk && s * s + t * t > 1.0) continue;
      Light at;
      at.type = LightType::point;
      at.position = light.position + s * half_u * u + t * half_v * v;
      const glm::dvec3 d = at.position - point.position;
      const double length_sq = glm::dot(d, d);
      const double weight = std::max(0.0, glm::dot(n, d)) * std::max(0.0, -glm::dot(normal, d)) / (length_sq * length_sq);
      if (!(weight > 0.0)) continue;
      total += weight;
      ReferenceShadowRay ray;
      if (!reference_shadow_ray_from(point.position, point.normal, at, eye, offset_scale, ray) ||
          reference_shadow_ray(shapes, ray.origin, ray.direction, ray.t_max) != RayOutcome::blocked)
        seen += cone ? weight * cone(at.position) : weight;
    }
  }
  return total > 0.0 ? seen / total : 1.0;
}

double reference_light_visibility(const SceneShapes& shapes, const Light& light, const SurfacePoint& point,
                                  const glm::dvec3& eye, double offset_scale, int grid) {
  AreaLight disk;
  disk.shape = AreaShape::disk;
  if (light.type == LightType::directional) {
    const glm::dvec3 l = -glm::normalize(light.direction);
    const double distance = 1e8 * (glm::length(point.position - eye) + 1.0);
    disk.position = point.position + distance * l;
    disk.direction = -l;
    disk.size = glm::dvec2(2.0 * distance * std::tan(light.angle_deg / 2.0 * std::numbers::pi / 180.0));
  } else {
    disk.position = light.position;
    disk.direction = point.position - light.position;
    disk.size = glm::dvec2(2.0 * light.radius);
  }
  if (light.type != LightType::spot) return reference_area_visibility(shapes, disk, point, eye, offset_scale, grid);
  return reference_area_visibility(shapes, disk, point, eye, offset_scale, grid, [&](const glm::dvec3& emitter_point) {
    return reference_spot_cone(light, glm::normalize(emitter_point - point.position));
  });
}

double reference_size_sin_sq(const Light& light, const glm::dvec3& position) {
  const double tangent = light.type == LightType::directional
                             ? std::tan(light.angle_deg / 2.0 * std::numbers::pi / 180.0)
                             : light.radius / glm::length(light.position - position);
  return tangent * tangent / (1.0 + tangent * tangent);
}

double reference_horizon_cosine(double c, double sin_sq, int steps) {
  // The disk about l = (sqrt(1 - c^2), 0, c), the normal z: rings of equal width in the angle from
  // l (weighted by their solid angle) and sectors, each direction's max(0, n.w) summed.
  // Wholly above or below the horizon: n.w's integral over the disk is c pi sin_sq exactly.
  if (c * c >= sin_sq) return std::max(c, 0.0);
  const double sigma = std::asin(std::sqrt(sin_sq)), sine = std::sqrt(std::max(0.0, 1.0 - c * c));
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) / steps * sigma, ring = std::sin(theta) * sigma / steps;
    for (int j = 0; j < steps; ++j) {
      const double phi = (j + 0.5) / steps * 2.0 * std::numbers::pi;
      // z of the direction at angle theta from l, azimuth phi about it (phi = 0 towards the normal)
      const double z = std::cos(theta) * c + std::sin(theta) * std::cos(phi) * sine;
      sum += std::max(0.0, z) * ring * 2.0 * std::numbers::pi / steps;
    }
  }
  return sum / (std::numbers::pi * sin_sq);
}

}  // namespace phongcl
