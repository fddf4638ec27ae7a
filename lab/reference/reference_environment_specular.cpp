#include "reference/reference_environment_specular.h"

#include "reference/reference_principled_v2.h"

namespace phongcl {

glm::dvec3 reference_environment_specular(const EnvironmentLight& light, const ReferenceMap& map, const SurfacePoint& point,
                                          const glm::dvec3& v) {
  const double length = glm::length(point.normal);
  if (!(length > 0.0) || !(glm::dot(point.normal, v) > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 n = point.normal / length;
  // Smith's masking tabulated once per alpha (within 1e-6 of its integral): this runs per texel.
  const double alpha = point.principled.roughness * point.principled.roughness;
  const auto masking = [alpha](double mu) { return smith_masking_table(alpha)(mu); };
  return integrate_environment(light, map, [&](const glm::dvec3& w) {
    if (!(glm::dot(n, w) > 0.0)) return glm::dvec3(0.0);  // a light behind the surface has no highlight
    if (point.specular_model == SpecularModel::principled)
      return reference_principled_specular_of_version(point.principled, n, v, w, masking);
    return glm::dvec3(reference_specular_lobe(point.specular_model, n, v, w, point.shininess));
  });
}

}  // namespace phongcl
