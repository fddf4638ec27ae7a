#include <algorithm>
#include <cmath>

#include "reference/reference.h"

namespace phongcl {

namespace {

// normalize() with the degenerate-input policy the kernel also follows: the zero vector maps to
// itself, and any other vector, however huge (1e300) or denormal (1e-310), to a unit vector.
// Dividing by the largest |component| first keeps the squares away from overflow and underflow.
glm::dvec3 robust_normalize(const glm::dvec3& x) {
  const double largest = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  if (largest == 0.0) return glm::dvec3(0.0);
  const glm::dvec3 scaled = x / largest;
  return scaled / std::sqrt(glm::dot(scaled, scaled));
}

}  // namespace

ShadingTerms reference_shade_point(const Scene& scene, const SurfacePoint& point) {
  ShadingTerms terms;
  terms.ambient = point.ka * scene.ambient;

  const glm::dvec3 n = robust_normalize(point.normal);
  // An eye exactly at the point gives v = 0, so v.r = 0 and the specular factor is pow(0, q).
  const glm::dvec3 v = robust_normalize(scene.camera.eye - point.position);

  for (const Light& light : scene.lights) {
    // l points from the surface towards the light; a directional light's direction is the way it
    // travels, hence the minus sign. Point lights are not attenuated with distance.
    const glm::dvec3 l = light.type == LightType::point ? robust_normalize(light.position - point.position)
                                                        : -robust_normalize(light.direction);
    const double ndl = glm::dot(n, l);
    if (!(ndl > 0.0)) continue;  // back-facing, zero normal, or light at the point

    terms.diffuse += point.kd * ndl * light.color;
    const glm::dvec3 r = 2.0 * ndl * n - l;
    // std::pow(0, 0) == 1, so q = 0 gives a full highlight even where v.r <= 0.
    const double specular = std::pow(std::max(0.0, glm::dot(v, r)), point.shininess);
    terms.specular += point.ks * specular * light.color;
  }
  return terms;
}

}  // namespace phongcl
