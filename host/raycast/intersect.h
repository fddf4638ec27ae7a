#pragma once
// Ray against one primitive, in the primitive's own space. Directions need not be unit length.
#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "raycast/camera.h"

namespace phongcl {

// The nearest hit with t_min < t < t_max, and the unit geometric normal there (either side).
struct PrimitiveHit {
  double t;
  glm::dvec3 normal;
};

std::optional<PrimitiveHit> intersect_sphere(const Ray& ray, const glm::dvec3& center, double radius,
                                             double t_min, double t_max);

// The plane dot(unit_normal, x) == offset.
std::optional<PrimitiveHit> intersect_plane(const Ray& ray, const glm::dvec3& unit_normal, double offset,
                                            double t_min, double t_max);

// Both faces are hit; the normal follows the counter-clockwise winding.
std::optional<PrimitiveHit> intersect_triangle(const Ray& ray, const std::array<glm::dvec3, 3>& vertices,
                                               double t_min, double t_max);

}  // namespace phongcl
