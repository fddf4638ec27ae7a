#include "reference/reference_environment_specular.h"

#include "reference/reference_principled.h"

namespace phongcl {

glm::dvec3 reference_environment_specular(const EnvironmentLight& light, const ReferenceMap& map, const SurfacePoint& point,
                                          const glm::dvec3& v) {
  const double length = glm::length(point.normal);
  if (!(length > 0.0) || !(glm::dot(point.normal, v) > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 n = point.normal / length;
  return integrate_environment(light, map, [&](const glm::dvec3& w) {
    if (!(glm::dot(n, w) > 0.0)) return glm::dvec3(0.0);  // a light behind the surface has no highlight
    const glm::dvec3 lobe = point.specular_model == SpecularModel::principled
                                ? reference_principled(point.principled, n, v, w).specular
                                : glm::dvec3(reference_specular_lobe(point.specular_model, n, v, w, point.shininess));
    return lobe;
  });
}

}  // namespace phongcl
