#include "stability/exact_shade.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "reference/reference.h"

namespace phongcl {

namespace {

using Vec = std::array<long double, 3>;

Vec widen(const glm::dvec3& x) { return {x.x, x.y, x.z}; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec scale(const Vec& a, long double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
long double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The policy the catalogue holds every implementation to: zero stays zero; any other finite
// vector, however large or denormal, becomes a unit vector (largest component divided out first).
Vec unit_or_zero(const Vec& x) {
  const long double largest = std::max({std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])});
  if (largest == 0) return {0, 0, 0};
  const Vec scaled = scale(x, 1 / largest);
  return scale(scaled, 1 / std::sqrt(dot(scaled, scaled)));
}

// max(0, a.b)^q for unit a and b, with pow(0, 0) = 1. Near the peak the logarithm comes from
// 1 - a.b = |a - b|^2/2, so even this oracle does not lose 1 - a.b to cancellation when q is 1e8.
long double power_of_cosine(const Vec& a, const Vec& b, long double q) {
  if (q == 0) return 1;
  const long double cosine = dot(a, b);
  if (!(cosine > 0)) return 0;
  const Vec a_minus_b = sub(a, b);
  const long double one_minus_cos = dot(a_minus_b, a_minus_b) / 2;
  return std::exp(q * (one_minus_cos < 0.5L ? std::log1p(-one_minus_cos) : std::log(cosine)));
}

// The material's lobe for a lit l (docs/shading.md "Specular models"): (v.r)^q with r = 2(n.l)n - l,
// or (n.h)^q with h = normalize(l + v) (0 when l + v = 0, q > 0); the normalised models times
// (q+2)/2 or (q+8)/8 and n.l.
long double specular_factor(SpecularModel model, const Vec& n, const Vec& v, const Vec& l, long double ndl,
                            long double q) {
  const bool blinn = model == SpecularModel::blinn_phong || model == SpecularModel::blinn_phong_normalized;
  const long double lobe = blinn ? power_of_cosine(n, unit_or_zero({l[0] + v[0], l[1] + v[1], l[2] + v[2]}), q)
                                 : power_of_cosine(v, sub(scale(n, 2 * ndl), l), q);
  switch (model) {
    case SpecularModel::phong_normalized: return (q + 2) / 2 * lobe * ndl;
    case SpecularModel::blinn_phong_normalized: return (q + 8) / 8 * lobe * ndl;
    default: return lobe;
  }
}


// 1 - cos(angle) without cancellation: 2 sin^2(angle / 2).
long double versine(long double angle) {
  const long double half_sine = std::sin(angle / 2);
  return 2 * half_sine * half_sine;
}

// F = falloff(d) * window(d) * cone(l) for a point or spot light (docs/shading.md "The formula").
// The cone compares 1 - c = |-l - a|^2 / 2 with 1 - cos(A/2) = 2 sin^2(A/4), as specular_factor
// does 1 - v.r: a cone of 1e-3 degrees, 1 - cos = 4e-11, keeps its full precision. Long double
// holds 1/d^3 for any float d, so F is never infinite here.
long double shape_factor(const Light& light, const Vec& to_light, const Vec& l) {
  const long double d = std::sqrt(dot(to_light, to_light));
  const long double falloff = std::pow(d, -static_cast<long double>(static_cast<int>(light.falloff)));
  long double window = 1;
  if (light.has_range()) {
    const long double x = d / light.range, t = std::clamp(1 - x * x * x * x, 0.0L, 1.0L);
    window = t * t;
  }
  long double cone = 1;
  if (light.type == LightType::spot) {
    const Vec off_axis = sub(scale(l, -1), unit_or_zero(widen(light.direction)));
    const long double off = dot(off_axis, off_axis) / 2;  // 1 - c
    const long double half_angle = light.cone_angle_deg / 2 * std::numbers::pi_v<long double> / 180;
    const long double inner = versine(half_angle), outer = versine(half_angle + light.penumbra_angle_deg * std::numbers::pi_v<long double> / 180);
    if (light.penumbra_angle_deg == 0) {
      cone = off <= inner ? 1 : 0;
    } else {
      const long double s = std::clamp((outer - off) / (outer - inner), 0.0L, 1.0L);
      cone = s * s * (3 - 2 * s);
    }
    // c^p = exp(p log(1 - off)): log1p keeps a large p's precision near the axis.
    if (light.cosine_power != 0 && cone != 0)
      cone *= off >= 1 ? 0 : std::exp(static_cast<long double>(light.cosine_power) * std::log1p(-off));
  }
  return falloff * window * cone;
}

}  // namespace

ExactColor exact_shade_pixel(const Scene& scene, const GBuffer& gbuffer, std::size_t index) {
  if (classify_pixel(gbuffer, index) != PixelClass::shaded) return widen(scene.background);
  // reference_surface only resolves which material values apply (table or per-pixel): no arithmetic.
  const SurfacePoint point = reference_surface(scene, gbuffer, index);
  const Vec position = widen(point.position);
  const Vec n = unit_or_zero(widen(point.normal));
  const Vec v = unit_or_zero(sub(widen(scene.camera.eye), position));

  Vec diffuse{0, 0, 0}, specular{0, 0, 0};
  for (const Light& light : scene.lights) {
    if (!light.reaches(point.material)) continue;  // light linking
    const bool positional = light.type != LightType::directional;
    const Vec to_light = positional ? sub(widen(light.position), position) : scale(widen(light.direction), -1);
    const Vec l = unit_or_zero(to_light);
    const long double ndl = dot(n, l);
    if (!(ndl > 0)) continue;
    const long double factor = positional ? shape_factor(light, to_light, l) : 1;
    const long double spec = specular_factor(point.specular_model, n, v, l, ndl, point.shininess);
    for (int c = 0; c < 3; ++c) {
      diffuse[c] += static_cast<long double>(light.color[c]) * ndl * factor;
      specular[c] += static_cast<long double>(light.color[c]) * spec * factor;
    }
  }
  ExactColor color;
  for (int c = 0; c < 3; ++c) {
    color[c] = static_cast<long double>(point.ka[c]) * scene.ambient[c] + static_cast<long double>(point.kd[c]) * diffuse[c] +
               static_cast<long double>(point.ks[c]) * specular[c];
  }
  return color;
}

}  // namespace phongcl
