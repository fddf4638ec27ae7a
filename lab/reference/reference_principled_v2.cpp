#include "reference/reference_principled_v2.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "reference/reference_oren_nayar.h"
#include "reference/simpson.h"

namespace phongcl {

using std::numbers::pi;

namespace {

double sqr(double x) { return x * x; }

// Smith's Lambda for GGX in closed form (Heitz 2014, eq. 72), for the albedo integrals' many directions;
// the lobe itself takes it from reference_smith_masking's numerical integral.
double closed_lambda(double alpha, double c) {
  return 0.5 * (std::sqrt(1.0 + alpha * alpha * std::max(1.0 / (c * c) - 1.0, 0.0)) - 1.0);
}

// (F(c) - F(1)) / (1 - F(1)) in [0, 1]: where the dielectric's Fresnel at c lies between its normal
// incidence and 1.
double fresnel_factor(double c, double eta) {
  const double f0 = reference_dielectric_fresnel(1.0, eta);
  return f0 < 1.0 ? std::clamp((reference_dielectric_fresnel(c, eta) - f0) / (1.0 - f0), 0.0, 1.0) : 0.0;
}

// Cycles reads E, E_avg and s from tables at fixed points, linearly between them (lookup_table_read,
// _2D, _3D): its BSDF is that interpolation. The reference integrates its own values at those points
// (roughness x / 31 or / 15, mu y / 31 or / 15, index axis z / 15, each clamped as Cycles clamps them),
// once per point, and interpolates the same way.
double table_axis(int k, int size, double high) { return std::clamp(static_cast<double>(k) / (size - 1), 1e-4, high); }

// The point below x in [0, 1] on an axis of `size` points, and the weight of the one above.
std::pair<int, double> table_cell(double x, int size) {
  const double at = std::clamp(x, 0.0, 1.0) * (size - 1);
  const int index = std::min(static_cast<int>(at), size - 1);
  return {index, at - index};
}

double albedo_at_point(int x, int y) {
  thread_local std::map<std::pair<int, int>, double> known;
  const auto key = std::pair{x, y};
  if (auto found = known.find(key); found != known.end()) return found->second;
  const double roughness = table_axis(x, 32, 1.0);
  return known[key] = std::clamp(reference_ggx_albedos(sqr(roughness), table_axis(y, 32, 1.0), 1.5).albedo, 0.0, 1.0);
}

// E_avg = 2 mu E(mu) over mu in [0, 1], 64 midpoints (smooth in mu).
double average_at_point(int x) {
  thread_local std::map<int, double> known;
  if (auto found = known.find(x); found != known.end()) return found->second;
  const double alpha = sqr(table_axis(x, 32, 1.0));
  double sum = 0.0;
  for (int k = 0; k < 64; ++k) {
    const double mu = (k + 0.5) / 64.0;
    sum += 2.0 * mu * reference_ggx_albedos(alpha, mu, 1.5).albedo;
  }
  return known[x] = std::clamp(sum / 64.0, 0.0, 1.0);
}

double factor_at_point(int x, int y, int z) {
  thread_local std::map<std::tuple<int, int, int>, double> known;
  const auto key = std::tuple{x, y, z};
  if (auto found = known.find(key); found != known.end()) return found->second;
  const double axis = table_axis(z, 16, 0.99), eta = (1.0 + axis * axis) / (1.0 - axis * axis);
  const double factor = reference_ggx_albedos(sqr(table_axis(x, 16, 1.0)), table_axis(y, 16, 1.0), eta).fresnel_factor;
  return known[key] = std::clamp(factor, 0.0, 1.0);
}

template <typename Point>
double interpolate(double x, int size, Point point) {
  const auto [index, t] = table_cell(x, size);
  return (1.0 - t) * point(index) + t * point(std::min(index + 1, size - 1));
}

double table_albedo(double roughness, double mu) {
  return interpolate(mu, 32, [&](int y) { return interpolate(roughness, 32, [&](int x) { return albedo_at_point(x, y); }); });
}

double table_average(double roughness) { return interpolate(roughness, 32, average_at_point); }

double table_factor(double roughness, double mu, double eta) {
  const double axis = std::sqrt(std::abs((eta - 1.0) / (eta + 1.0)));
  return interpolate(axis, 16, [&](int z) {
    return interpolate(mu, 16, [&](int y) { return interpolate(roughness, 16, [&](int x) { return factor_at_point(x, y, z); }); });
  });
}

// The F82-tint metal's Fresnel (Kutz et al. 2021): Schlick's less b c (1 - c)^6, b making the value at
// cos = 1/7 the tint times Schlick's there.
glm::dvec3 f82_fresnel(double c, const glm::dvec3& f0, const glm::dvec3& b) {
  const double m = std::clamp(1.0 - c, 0.0, 1.0);
  return glm::clamp(f0 + (1.0 - f0) * std::pow(m, 5.0) - b * c * std::pow(m, 6.0), 0.0, 1.0);
}

glm::dvec3 f82_b(const glm::dvec3& f0, const glm::dvec3& tint) {
  const double c = 1.0 / 7.0, m = 1.0 - c;
  return (f0 + (1.0 - f0) * std::pow(m, 5.0)) * (1.0 - tint) / (c * std::pow(m, 6.0));
}

// What the node's inputs make of the lobes before any light (svm/closure.h).
struct Lobes {
  double alpha = 0.0, metallic = 0.0, eta = 1.0;
  bool layer = false;
  glm::dvec3 metal_f0{0.0}, metal_b{0.0}, dielectric_f0{0.0};
  glm::dvec3 metal_scale{0.0}, dielectric_boost{1.0};  // the energy compensations
  double missing = 0.0;
};

Lobes compute_lobes(const Material& m, double mu) {
  Lobes lobes;
  lobes.alpha = m.roughness * m.roughness;
  lobes.metallic = m.metallic > 1e-5 ? m.metallic : 0.0;
  double f0 = reference_dielectric_fresnel(1.0, m.ior);
  lobes.eta = m.ior;
  if (m.specular_ior_level != 0.5) {
    f0 *= 2.0 * m.specular_ior_level;
    const double root = std::sqrt(std::clamp(f0, 0.0, 0.99));
    lobes.eta = (1.0 + root) / (1.0 - root);
  }
  lobes.layer = static_cast<float>(lobes.eta) != 1.0f;
  lobes.dielectric_f0 = glm::clamp(f0 * m.specular_tint_color, 0.0, 1.0);
  lobes.metal_f0 = glm::min(m.base_color, glm::dvec3(1.0));
  const glm::dvec3 edge = glm::min(m.specular_tint_color, glm::dvec3(1.0));
  lobes.metal_b = edge == glm::dvec3(1.0) ? glm::dvec3(0.0) : f82_b(lobes.metal_f0, edge);
  // Kulla and Conty's compensation: 1 + Fms (1 - E) / E, Fms = Fss E_avg / (1 - Fss (1 - E_avg)), Fss the
  // lobe's hemispherical mean Fresnel: the F82 model's by Simpson's rule, the dielectric's Cycles' fit
  // (fresnel_dielectric_Fss, part of the model).
  const double e = table_albedo(m.roughness, mu), e_avg = table_average(m.roughness);
  lobes.missing = (1.0 - e) / e;
  auto boost = [&](const glm::dvec3& fss) { return 1.0 + fss * e_avg / (1.0 - fss * (1.0 - e_avg)) * lobes.missing; };
  const glm::dvec3 metal_mean =
      simpson([&](double c) { return 2.0 * c * f82_fresnel(c, lobes.metal_f0, lobes.metal_b); }, 0.0, 1.0, 512);
  lobes.metal_scale = lobes.metallic * boost(metal_mean);
  const double eta = lobes.eta, index_f0 = reference_dielectric_fresnel(1.0, eta);
  const double fit = (eta - 1.0) / (4.08567 + 1.00071 * eta);
  const double mean_factor = std::clamp((fit - index_f0) / (1.0 - index_f0), 0.0, 1.0);
  lobes.dielectric_boost = boost(lobes.dielectric_f0 + (1.0 - lobes.dielectric_f0) * mean_factor);
  return lobes;
}

// compute_lobes of the last material and cosine asked for on this thread: an integral over directions
// asks for the same ones at every direction.
const Lobes& lobes_at(const Material& m, double mu) {
  struct Last {
    double mu = -1.0, roughness = 0.0, metallic = 0.0, ior = 0.0, level = 0.0;
    glm::dvec3 base{0.0}, tint{0.0};
    Lobes lobes;
  };
  static thread_local Last last;
  if (mu != last.mu || m.roughness != last.roughness || m.metallic != last.metallic || m.ior != last.ior ||
      m.specular_ior_level != last.level || m.base_color != last.base || m.specular_tint_color != last.tint)
    last = {mu, m.roughness, m.metallic, m.ior, m.specular_ior_level, m.base_color, m.specular_tint_color, compute_lobes(m, mu)};
  return last.lobes;
}

}  // namespace

GgxAlbedos reference_ggx_albedos(double alpha, double mu, double eta) {
  // Over GGX's normals h: D(h) cos(theta_h) dw_h = du dphi / (2 pi) with tan^2(theta_h) = alpha^2 u / (1 - u).
  // l = the mirror of v about h, dw_l = 4 h.v dw_h: E = int D G2 h.v / (mu cos) , and the visible normals'
  // mean of the factor = int G1(v) D factor h.v / (mu cos), both over l above the horizon. v lies in the xz
  // plane: phi over [0, pi] by symmetry. h.v / cos grows as tan = alpha sqrt(u / (1 - u)), an integrable
  // singularity at u = 1 that the midpoint rule would truncate (2% at grazing views): u = 1 - w^2,
  // du = 2 w dw, makes it smooth. 400 x 100 midpoints in (w, phi).
  const glm::dvec3 v(std::sqrt(std::max(1.0 - mu * mu, 0.0)), 0.0, mu);
  const double lambda_v = closed_lambda(alpha, mu);
  const int nu = 400, nphi = 100;
  GgxAlbedos sums;
  for (int a = 0; a < nu; ++a) {
    const double w = (a + 0.5) / nu, jacobian = 2.0 * w;
    const double tan_sq = alpha * alpha * (1.0 - w * w) / (w * w), cos_t = 1.0 / std::sqrt(1.0 + tan_sq);
    const double sin_t = std::sqrt(std::max(1.0 - cos_t * cos_t, 0.0));
    for (int b = 0; b < nphi; ++b) {
      const double phi = pi * (b + 0.5) / nphi;
      const glm::dvec3 h(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
      const double h_dot_v = glm::dot(h, v);
      if (!(h_dot_v > 0.0)) continue;
      const double l_z = 2.0 * h_dot_v * h.z - v.z;
      if (!(l_z > 0.0)) continue;
      const double weight = jacobian * h_dot_v / (mu * cos_t);
      sums.albedo += weight / (1.0 + lambda_v + closed_lambda(alpha, l_z));
      sums.fresnel_factor += weight / (1.0 + lambda_v) * fresnel_factor(h_dot_v, eta);
    }
  }
  sums.albedo /= static_cast<double>(nu) * nphi;
  sums.fresnel_factor /= static_cast<double>(nu) * nphi;
  return sums;
}

glm::dvec3 reference_principled_v2_lambert(const Material& material, double mu) {
  const Lobes lobes = lobes_at(material, mu);
  double share = 1.0;
  if (lobes.layer) {
    // closure_layering_weight: 1 - the layer's largest albedo channel, mix(f0, 1, s) times the
    // compensation's darkening boost / (1 + missing).
    const double s = table_factor(material.roughness, mu, lobes.eta);
    const glm::dvec3 albedo = (lobes.dielectric_f0 + (1.0 - lobes.dielectric_f0) * s) * lobes.dielectric_boost /
                              (1.0 + lobes.missing);
    share = std::clamp(1.0 - std::max({albedo.r, albedo.g, albedo.b}), 0.0, 1.0);
  }
  return material.base_color * (1.0 - lobes.metallic) * share;
}

namespace {

bool rough_diffuse(const Material& material) { return material.diffuse_roughness >= 1e-5; }

// Cycles' Oren-Nayar takes the base colour saturated as its albedo (bsdf_oren_nayar_param).
glm::dvec3 diffuse_albedo(const Material& material) { return glm::clamp(material.base_color, 0.0, 1.0); }

// Version 2's specular light alone: the integrals over emitters and texels need no diffuse.
glm::dvec3 v2_specular(const Material& material, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l,
                       const std::function<double(double)>& masking) {
  const double ndl = glm::dot(n, l), ndv = glm::dot(n, v);
  if (!(ndl > 0.0)) return glm::dvec3(0.0);
  const Lobes lobes = lobes_at(material, std::clamp(ndv, 0.0, 1.0));
  if (!(ndv > 0.0) || sqr(lobes.alpha) <= 2e-10) return glm::dvec3(0.0);
  const glm::dvec3 h = glm::normalize(l + v);
  const double ldh = glm::dot(l, h), c = glm::dot(n, h);
  // GGX's density from its slope distribution (Heitz 2014, eq. 12) and G2 = 1 / (1 + Lambda_v + Lambda_l).
  const double t_sq = (1.0 - c * c) / (c * c), shape = 1.0 + t_sq / sqr(lobes.alpha);
  const double density = 1.0 / (pi * sqr(lobes.alpha) * sqr(shape) * sqr(c * c));
  const double lambda_v = 1.0 / masking(ndv) - 1.0, lambda_l = 1.0 / masking(ndl) - 1.0;
  const double brdf_pi = pi * density / (1.0 + lambda_v + lambda_l) / (4.0 * ndv);
  const glm::dvec3 dielectric =
      lobes.layer ? (1.0 - lobes.metallic) * lobes.dielectric_boost *
                        (lobes.dielectric_f0 + (1.0 - lobes.dielectric_f0) * fresnel_factor(ldh, lobes.eta))
                  : glm::dvec3(0.0);
  return brdf_pi * (lobes.metal_scale * f82_fresnel(ldh, lobes.metal_f0, lobes.metal_b) + dielectric);
}

}  // namespace

glm::dvec3 reference_principled_v2_over_lambert(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                const glm::dvec3& l) {
  if (!rough_diffuse(material)) return glm::dvec3(1.0);
  return reference_oren_nayar_over_lambert(material.diffuse_roughness, diffuse_albedo(material), n, v, l);
}

glm::dvec3 reference_principled_v2_white_sky(const Material& material, double mu) {
  if (!rough_diffuse(material)) return glm::dvec3(1.0);
  return reference_oren_nayar_white_sky(material.diffuse_roughness, diffuse_albedo(material), mu);
}

PrincipledLight reference_principled_v2(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                        const glm::dvec3& l) {
  const double alpha = material.roughness * material.roughness;
  return reference_principled_v2(material, n, v, l, [alpha](double mu) { return reference_smith_masking(alpha, mu); });
}

PrincipledLight reference_principled_v2(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                        const glm::dvec3& l, const std::function<double(double)>& masking) {
  PrincipledLight light;
  const double ndl = glm::dot(n, l), ndv = glm::dot(n, v);
  if (!(ndl > 0.0)) return light;
  light.diffuse = reference_principled_v2_lambert(material, std::clamp(ndv, 0.0, 1.0)) *
                  (rough_diffuse(material) ? reference_oren_nayar(material.diffuse_roughness, diffuse_albedo(material), n, v, l)
                                           : glm::dvec3(ndl));
  light.specular = v2_specular(material, n, v, l, masking);
  return light;
}

glm::dvec3 reference_principled_specular_of_version(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                    const glm::dvec3& l, const std::function<double(double)>& masking) {
  return material.version == 2 ? v2_specular(material, n, v, l, masking)
                               : reference_principled(material, n, v, l, masking).specular;
}

PrincipledLight reference_principled_of_version(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                const glm::dvec3& l) {
  return material.version == 2 ? reference_principled_v2(material, n, v, l) : reference_principled(material, n, v, l);
}

PrincipledLight reference_principled_of_version(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                const glm::dvec3& l, const std::function<double(double)>& masking) {
  return material.version == 2 ? reference_principled_v2(material, n, v, l, masking)
                               : reference_principled(material, n, v, l, masking);
}

}  // namespace phongcl
