#include "reference/reference_principled.h"

#include "reference/reference_area.h"
#include "reference/reference_principled_v2.h"
#include "reference/simpson.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <glm/geometric.hpp>

namespace phongcl {

using std::numbers::pi;

// GGX's density as its slope distribution P22(t) = 1 / (pi alpha^2 (1 + t^2 / alpha^2)^2) at slope
// t = tan, over cos^4 (Heitz 2014, eq. 12).
double reference_ggx_density(double alpha, double c) {
  const double t_sq = (1.0 - c * c) / (c * c);
  const double shape = 1.0 + t_sq / (alpha * alpha);
  return 1.0 / (pi * alpha * alpha * shape * shape * c * c * c * c);
}

double reference_smith_masking(double alpha, double mu) {
  // Lambda = (1 / a) int_a^inf (x - a) P2(x) dx, a = cot(theta), P2 the slope distribution's marginal
  // 1 / (2 alpha (1 + x^2 / alpha^2)^(3/2)). With x = alpha tan(phi) the integrand is smooth on
  // [atan(a / alpha), pi / 2]: Simpson's rule with 2048 intervals, error far below 1e-9 there.
  const double a = mu / std::sqrt(std::max(1.0 - mu * mu, 0.0));
  if (!std::isfinite(a)) return 1.0;
  auto integrand = [&](double phi) {
    const double x = alpha * std::tan(phi);
    const double marginal = 1.0 / (2.0 * alpha * std::pow(1.0 + x * x / (alpha * alpha), 1.5));
    const double dx = alpha / (std::cos(phi) * std::cos(phi));
    return (x - a) * marginal * dx;  // at pi / 2 (cos 6e-17 in double) this is its limit, alpha / 2
  };
  const double lambda = simpson(integrand, std::atan(a / alpha), pi / 2.0, 2048) / a;
  return 1.0 / (1.0 + lambda);
}

double reference_dielectric_fresnel(double c, double eta) {
  const double sin_t_sq = (1.0 - c * c) / (eta * eta);
  if (sin_t_sq >= 1.0) return 1.0;
  const double t = std::sqrt(1.0 - sin_t_sq);
  const double rs = (c - eta * t) / (c + eta * t), rp = (eta * c - t) / (eta * c + t);
  return 0.5 * (rs * rs + rp * rp);
}

namespace {
constexpr int masking_nodes = 4097;
}  // namespace

SmithMaskingTable::SmithMaskingTable(double alpha) : nodes_(masking_nodes, 0.0) {
  for (int k = 1; k < masking_nodes; ++k) nodes_[k] = reference_smith_masking(alpha, double(k) / (masking_nodes - 1));
}

double SmithMaskingTable::operator()(double mu) const {
  const double x = std::clamp(mu, 0.0, 1.0) * (masking_nodes - 1);
  const int k = std::min(int(x), masking_nodes - 2);
  const double t = x - k;
  return nodes_[k] * (1.0 - t) + nodes_[k + 1] * t;
}

const SmithMaskingTable& smith_masking_table(double alpha) {
  static thread_local std::map<double, SmithMaskingTable> tables;
  auto found = tables.find(alpha);
  if (found == tables.end()) found = tables.emplace(alpha, SmithMaskingTable(alpha)).first;
  return found->second;
}

PrincipledLight reference_principled(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                     const glm::dvec3& l) {
  const double alpha = material.roughness * material.roughness;
  return reference_principled(material, n, v, l, [alpha](double mu) { return reference_smith_masking(alpha, mu); });
}

PrincipledLight reference_principled(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                     const glm::dvec3& l, const std::function<double(double)>& masking) {
  PrincipledLight light;
  const double ndl = glm::dot(n, l), ndv = glm::dot(n, v);
  if (!(ndl > 0.0)) return light;
  const glm::dvec3 h = glm::normalize(l + v);
  const double ldh = glm::dot(l, h);
  // Burley 2015, "Extending the Disney BRDF to a BSDF with Integrated Subsurface Scattering", section
  // 2.3: Lambert's part (1 - FL / 2)(1 - FV / 2) and the retro-reflection
  // R (FL + FV + FL FV (R - 1)), R = 2 roughness cos^2(theta_d), F = (1 - cos)^5.
  auto weight = [](double c) { return std::pow(std::clamp(1.0 - c, 0.0, 1.0), 5.0); };
  const double fl = weight(ndl), fv = weight(ndv), retro = 2.0 * material.roughness * ldh * ldh;
  const double burley = (1.0 - fl / 2.0) * (1.0 - fv / 2.0) + retro * (fl + fv + fl * fv * (retro - 1.0));
  light.diffuse = material.base_color * (1.0 - material.metallic) * (burley * ndl);
  const double alpha = material.roughness * material.roughness;
  if (!(ndv > 0.0) || alpha * alpha <= 1e-7) return light;
  // Walter et al. 2007: f = D G F / (4 n.l n.v); pi f n.l.
  const double brdf_pi = pi * reference_ggx_density(alpha, glm::dot(n, h)) * masking(ndv) * masking(ndl) / (4.0 * ndv);
  // v1's Fresnel: the dielectric's of the index that Specular implies, remapped from [F(1), 1] to
  // [cspec0, 1]; cspec0 mixes 0.08 Specular (tinted) into the base colour by metallic.
  const double eta = 2.0 / (1.0 - std::sqrt(0.08 * material.specular)) - 1.0;
  const double f0 = reference_dielectric_fresnel(1.0, eta);
  const double fh = (reference_dielectric_fresnel(ldh, eta) - f0) / (1.0 - f0);
  const glm::dvec3 base = material.base_color;
  const double luminance = 0.3 * base.r + 0.6 * base.g + 0.1 * base.b;
  const glm::dvec3 tint = luminance > 0.0 ? base / luminance : glm::dvec3(1.0);
  const glm::dvec3 dielectric = 0.08 * material.specular * ((1.0 - material.specular_tint) * glm::dvec3(1.0) +
                                                            material.specular_tint * tint);
  const glm::dvec3 cspec0 = (1.0 - material.metallic) * dielectric + material.metallic * base;
  light.specular = brdf_pi * (cspec0 * (1.0 - fh) + glm::dvec3(fh));
  return light;
}

glm::dvec3 reference_principled_area(const Material& material, const AreaLight& light, const glm::dvec3& position,
                                     const glm::dvec3& n, const glm::dvec3& v) {
  const double alpha = material.roughness * material.roughness;
  if (alpha * alpha <= 1e-7) return glm::dvec3(0.0);
  const SmithMaskingTable& masking = smith_masking_table(alpha);
  const auto lobe = [&](const glm::dvec3& w) {
    return reference_principled_specular_of_version(material, n, v, w, [&](double mu) { return masking(mu); });
  };
  // GGX's peak is about as wide as Phong's of exponent 2 / alpha^2; it has no kink above the horizon.
  return reference_area_lobe(light, position, n, v, lobe, 2.0 / (alpha * alpha), false);
}

}  // namespace phongcl
