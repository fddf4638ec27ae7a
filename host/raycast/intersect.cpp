#include "raycast/intersect.h"

#include <cmath>

namespace phongcl {
namespace {

// The roots t_near <= t_far of |origin + t * direction - center| == radius, if real.
std::optional<std::array<double, 2>> ball_interval(const Ray& ray, const glm::dvec3& center, double radius) {
  const glm::dvec3 to_origin = ray.origin - center;
  const double a = glm::dot(ray.direction, ray.direction);
  const double half_b = glm::dot(to_origin, ray.direction);
  const double c = glm::dot(to_origin, to_origin) - radius * radius;
  const double discriminant = half_b * half_b - a * c;
  if (discriminant < 0.0) return std::nullopt;
  const double root = std::sqrt(discriminant);
  return std::array<double, 2>{(-half_b - root) / a, (-half_b + root) / a};
}

}  // namespace

std::optional<PrimitiveHit> intersect_sphere(const Ray& ray, const glm::dvec3& center, double radius,
                                             double t_min, double t_max) {
  const auto interval = ball_interval(ray, center, radius);
  if (!interval) return std::nullopt;
  // The far root counts when the ray starts inside the sphere.
  const double t = (*interval)[0] > t_min ? (*interval)[0] : (*interval)[1];
  if (!(t > t_min && t < t_max)) return std::nullopt;
  return PrimitiveHit{t, (ray.origin + t * ray.direction - center) / radius};
}

std::optional<PrimitiveHit> intersect_plane(const Ray& ray, const glm::dvec3& unit_normal, double offset,
                                            double t_min, double t_max) {
  const double approach = glm::dot(unit_normal, ray.direction);
  if (approach == 0.0) return std::nullopt;  // parallel
  const double t = (offset - glm::dot(unit_normal, ray.origin)) / approach;
  if (!(t > t_min && t < t_max)) return std::nullopt;
  return PrimitiveHit{t, unit_normal};
}

std::optional<PrimitiveHit> intersect_triangle(const Ray& ray, const std::array<glm::dvec3, 3>& vertices,
                                               double t_min, double t_max) {
  // Möller-Trumbore: solve origin + t * direction == v0 + u * edge1 + v * edge2.
  const glm::dvec3 edge1 = vertices[1] - vertices[0];
  const glm::dvec3 edge2 = vertices[2] - vertices[0];
  const glm::dvec3 p = glm::cross(ray.direction, edge2);
  const double determinant = glm::dot(edge1, p);
  if (determinant == 0.0) return std::nullopt;  // parallel to the triangle's plane
  const double inverse = 1.0 / determinant;
  const glm::dvec3 to_origin = ray.origin - vertices[0];
  const double u = glm::dot(to_origin, p) * inverse;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const glm::dvec3 q = glm::cross(to_origin, edge1);
  const double v = glm::dot(ray.direction, q) * inverse;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = glm::dot(edge2, q) * inverse;
  if (!(t > t_min && t < t_max)) return std::nullopt;
  return PrimitiveHit{t, glm::normalize(glm::cross(edge1, edge2))};
}

}  // namespace phongcl
