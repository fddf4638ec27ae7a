#include "reference/reference_oren_nayar.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "reference/simpson.h"

namespace phongcl {

using std::numbers::pi;

namespace {

double single_a(double sigma) { return 1.0 / (pi + sigma * (pi / 2.0 - 2.0 / 3.0)); }

// Pi times Ems: OpenPBR's multiple scattering's albedo-dependent factor (bsdf_oren_nayar_param).
glm::dvec3 multiple_factor(double sigma, const glm::dvec3& albedo) {
  const double average = reference_oren_nayar_average(sigma);
  return albedo * albedo * (average / (1.0 - average)) / (1.0 - albedo * (1.0 - average));
}

}  // namespace

double reference_oren_nayar_albedo(double sigma, double c) {
  // Over view directions at cosine u and azimuth phi from l's: t = sin_l sin_v cos(phi), divided by
  // max(c, u) where positive. Its integral over phi is sin_l sin_v (2 / max(c, u) - 2) (cos(phi) > 0
  // integrates to 2, the rest to -2), a's is 2 pi a. What remains is smooth in theta_v on either side of
  // theta_l: Simpson's rule on each.
  const double a = single_a(sigma), b = sigma * a;
  const double sin_l = std::sqrt(std::max(1.0 - c * c, 0.0)), theta_l = std::acos(std::clamp(c, 0.0, 1.0));
  const auto integrand = [&](double theta) {
    const double u = std::cos(theta), sin_v = std::sin(theta);
    const double azimuth = 2.0 * pi * a + b * sin_l * sin_v * (2.0 / std::max({c, u, 1e-300}) - 2.0);
    return azimuth * u * sin_v;
  };
  return simpson(integrand, 0.0, theta_l, 256) + simpson(integrand, theta_l, pi / 2.0, 256);
}

double reference_oren_nayar_average(double sigma) {
  thread_local std::map<double, double> known;
  if (auto found = known.find(sigma); found != known.end()) return found->second;
  return known[sigma] = simpson([sigma](double c) { return 2.0 * c * reference_oren_nayar_albedo(sigma, c); }, 0.0, 1.0, 128);
}

glm::dvec3 reference_oren_nayar_over_lambert(double sigma, const glm::dvec3& albedo, const glm::dvec3& n,
                                             const glm::dvec3& v, const glm::dvec3& l) {
  const double nl = std::clamp(glm::dot(n, l), 1e-4, 1.0), nv = std::clamp(glm::dot(n, v), 0.0, 1.0);
  const double a = single_a(sigma), b = sigma * a;
  double t = glm::dot(l, v) - nl * nv;
  if (t > 0.0) t /= std::max(nl, nv);
  const glm::dvec3 multiple = multiple_factor(sigma, albedo) * (1.0 - reference_oren_nayar_albedo(sigma, nv)) *
                              (1.0 - reference_oren_nayar_albedo(sigma, nl));
  return pi * (a + b * t) + multiple;
}

glm::dvec3 reference_oren_nayar(double sigma, const glm::dvec3& albedo, const glm::dvec3& n, const glm::dvec3& v,
                                const glm::dvec3& l) {
  const double nl = glm::dot(n, l);
  return nl > 0.0 ? nl * reference_oren_nayar_over_lambert(sigma, albedo, n, v, l) : glm::dvec3(0.0);
}

glm::dvec3 reference_oren_nayar_white_sky(double sigma, const glm::dvec3& albedo, double mu) {
  const double single = reference_oren_nayar_albedo(sigma, mu);
  return single + multiple_factor(sigma, albedo) * (1.0 - single) * (1.0 - reference_oren_nayar_average(sigma));
}

}  // namespace phongcl
