#include "fit/ggx_lobe.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace phongcl {

using std::numbers::pi;

GgxLobe::GgxLobe(double roughness) : alpha_(roughness * roughness), masking_(&smith_masking_table(alpha_)) {
  material_.specular_model = SpecularModel::principled;
  material_.base_color = glm::dvec3(1.0);
  material_.metallic = 1.0;
  material_.roughness = roughness;
}

double GgxLobe::value(const glm::dvec3& v, const glm::dvec3& l) const {
  if (!(v.z > 0.0)) return 0.0;
  const SmithMaskingTable& masking = *masking_;
  return reference_principled(material_, glm::dvec3(0.0, 0.0, 1.0), v, l, [&](double mu) { return masking(mu); }).specular.x;
}

glm::dvec3 GgxLobe::sample(const glm::dvec3& v, double xi1, double xi2) const {
  const double tan_sq = alpha_ * alpha_ * xi1 / (1.0 - xi1);
  const double cos_h = 1.0 / std::sqrt(1.0 + tan_sq), sin_h = std::sqrt(std::max(1.0 - cos_h * cos_h, 0.0));
  const double phi = 2.0 * pi * xi2;
  const glm::dvec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
  return 2.0 * glm::dot(v, h) * h - v;
}

double GgxLobe::sample_density(const glm::dvec3& v, const glm::dvec3& l) const {
  const glm::dvec3 sum = v + l;
  if (!(glm::dot(sum, sum) > 0.0)) return 0.0;
  const glm::dvec3 h = glm::normalize(sum);
  const double v_dot_h = glm::dot(v, h);
  return v_dot_h > 0.0 && h.z > 0.0 ? reference_ggx_density(alpha_, h.z) * h.z / (4.0 * v_dot_h) : 0.0;
}

}  // namespace phongcl
