#include <algorithm>
#include <cmath>
#include <numbers>

#include "reference/reference.h"
#include "reference/reference_area.h"
#include "reference/reference_environment.h"
#include "reference/reference_environment_specular.h"
#include "reference/reference_principled.h"
#include "reference/reference_principled_v2.h"
#include "reference/reference_soft_shadows.h"

namespace phongcl {

using std::numbers::pi;

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

// falloff(d) * window(d) * cone(l) (docs/shading.md "The formula"), straight from the formula;
// without `with_cone` the cone is left out (a soft spot's is in its visible fraction).
double light_factor(const Light& light, const glm::dvec3& position, const glm::dvec3& l, bool with_cone) {
  const double d = glm::length(light.position - position);
  const double falloff = std::pow(d, -static_cast<double>(static_cast<int>(light.falloff)));
  double window = 1.0;
  if (light.has_range()) {
    const double t = std::clamp(1.0 - std::pow(d / light.range, 4.0), 0.0, 1.0);
    window = t * t;
  }
  const double cone = light.type == LightType::spot && with_cone ? reference_spot_cone(light, l) : 1.0;
  // 1/d^k may be +Inf where the window or cone is 0: the light contributes nothing there.
  return window * cone == 0.0 ? 0.0 : falloff * window * cone;
}

// x * y where an infinite factor meeting an exact zero gives 0 (a colour or coefficient of 0 takes
// nothing from even an overflowing light).
glm::dvec3 product(const glm::dvec3& x, const glm::dvec3& y) {
  glm::dvec3 result;
  for (int c = 0; c < 3; ++c) result[c] = x[c] == 0.0 || y[c] == 0.0 ? 0.0 : x[c] * y[c];
  return result;
}

}  // namespace

double reference_spot_cone(const Light& light, const glm::dvec3& l) {
  const double c = glm::dot(-l, glm::normalize(light.direction));
  const double half_angle = light.cone_angle_deg / 2.0 * pi / 180.0;
  const double ci = std::cos(half_angle);
  const double co = std::cos(half_angle + light.penumbra_angle_deg * pi / 180.0);
  double cone = 0.0;
  if (light.penumbra_angle_deg == 0.0) {
    cone = c >= ci ? 1.0 : 0.0;
  } else {
    const double s = std::clamp((c - co) / (ci - co), 0.0, 1.0);
    cone = s * s * (3.0 - 2.0 * s);
  }
  // The cosine power (Arnold's cosine_power; p = 1 is Blender 3.x Cycles' spot): std::pow(x, 0) = 1.
  return cone * std::pow(std::max(0.0, c), light.cosine_power);
}

double reference_specular_lobe(SpecularModel model, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l,
                               double shininess) {
  const double q = shininess;
  switch (model) {
    case SpecularModel::phong:
    case SpecularModel::phong_normalized: {
      const glm::dvec3 r = 2.0 * glm::dot(n, l) * n - l;
      // std::pow(0, 0) == 1, so q = 0 gives a full highlight even where v.r <= 0.
      const double highlight = std::pow(std::max(0.0, glm::dot(v, r)), q);
      return model == SpecularModel::phong ? highlight : (q + 2.0) / 2.0 * highlight * glm::dot(n, l);
    }
    case SpecularModel::blinn_phong:
    case SpecularModel::blinn_phong_normalized: {
      const glm::dvec3 h = robust_normalize(l + v);
      const double highlight = std::pow(std::max(0.0, glm::dot(n, h)), q);
      return model == SpecularModel::blinn_phong ? highlight : (q + 8.0) / 8.0 * highlight * glm::dot(n, l);
    }
    case SpecularModel::principled: return 0.0;  // not a lobe ks scales: reference_principled.h
  }
  return 0.0;
}

ShadingTerms reference_shade_point(const Scene& scene, const SurfacePoint& point, const LightReach& reaches,
                                   const SoftVisibility& soft) {
  ShadingTerms terms;
  terms.ambient = point.ka * scene.ambient;

  const glm::dvec3 n = robust_normalize(point.normal);
  // An eye exactly at the point gives v = 0: v.r = 0 and Phong's factor is pow(0, q); Blinn's h is l.
  const glm::dvec3 v = robust_normalize(scene.camera.eye - point.position);

  glm::dvec3 diffuse(0.0), specular(0.0);  // sums of Li * F * (n.l) and Li * F * lobe
  glm::dvec3 principled_diffuse(0.0), principled_specular(0.0);  // a Principled point's, coloured
  for (const Light& light : scene.lights) {
    if (!light.reaches(point.material)) continue;
    const bool sized = soft.sized && light.shadows && light.has_size();
    if (!sized && reaches && light.shadows && !reaches(point, light)) continue;
    // l points from the surface towards the light; a directional light's direction is the way it
    // travels, hence the minus sign.
    const bool positional = light.type != LightType::directional;
    const glm::dvec3 l = positional ? robust_normalize(light.position - point.position) : -robust_normalize(light.direction);
    const double ndl = glm::dot(n, l);
    // A light with a size whose shadow is soft lights a little past the horizon, as its emitter
    // does; its highlight stays where n.l > 0.
    const double lit = sized && n != glm::dvec3(0.0) ? reference_horizon_cosine(ndl, reference_size_sin_sq(light, point.position))
                                                     : std::max(ndl, 0.0);
    if (!(lit > 0.0)) continue;  // back-facing, zero normal, or light at the point
    const double factor =
        (positional ? light_factor(light, point.position, l, !sized) : 1.0) * (sized ? soft.sized(point, light) : 1.0);
    if (factor == 0.0) continue;

    if (point.specular_model == SpecularModel::principled) {
      // Smith's masking tabulated once per alpha (within 1e-6 of its integral): this runs per pixel and light.
      const double alpha = point.principled.roughness * point.principled.roughness;
      const PrincipledLight lobes = reference_principled_of_version(
          point.principled, n, v, l, [alpha](double mu) { return smith_masking_table(alpha)(mu); });
      principled_diffuse += product(light.color, lobes.diffuse * factor);
      principled_specular += product(light.color, lobes.specular * factor);
      continue;
    }
    diffuse += product(light.color, glm::dvec3(lit * factor));
    const double highlight = ndl > 0.0 ? reference_specular_lobe(point.specular_model, n, v, l, point.shininess) : 0.0;
    if (highlight > 0.0) specular += product(light.color, glm::dvec3(highlight * factor));
  }
  // Area lights: E and S by quadrature over the emitter (reference_area.h).
  for (const AreaLight& light : scene.area_lights) {
    if (n == glm::dvec3(0.0)) break;
    const bool traced = soft.area && light.shadows;
    if (!traced && reaches && light.shadows && !reaches(point, area_shadow_light(light))) continue;
    const AreaIntegrals integrals = reference_area_integrals(light, point.position, n, v, point.specular_model, point.shininess);
    const double window = area_range_window(light, point.position) * (traced ? soft.area(point, light) : 1.0);
    // A Principled v2 point's Oren-Nayar over Lambert toward the light's centre, as the kernel.
    const glm::dvec3 over_lambert =
        point.specular_model == SpecularModel::principled && point.principled.version == 2
            ? reference_principled_v2_over_lambert(point.principled, n, v, robust_normalize(light.position - point.position))
            : glm::dvec3(1.0);
    diffuse += product(light.color, over_lambert * (integrals.irradiance * window));
    specular += product(light.color, glm::dvec3(integrals.highlight * window));
    if (point.specular_model == SpecularModel::principled)
      principled_specular += product(light.color, reference_principled_area(point.principled, light, point.position, n, v) * window);
  }
  // The environment: its irradiance by brute force over the map (reference_environment.h).
  if (scene.environment && n != glm::dvec3(0.0)) {
    const EnvironmentLight& world = *scene.environment;
    const glm::dvec3 sky = soft.environment && world.shadows ? soft.environment(point)
                                                             : reference_environment_light(world, reference_map(world), n);
    // A Principled v2 point's Oren-Nayar under a white world over Lambert's, as the kernel.
    diffuse += point.specular_model == SpecularModel::principled && point.principled.version == 2
                   ? product(sky, reference_principled_v2_white_sky(point.principled, std::clamp(glm::dot(n, v), 0.0, 1.0)))
                   : sky;
    // Its specular: the material's own lobe against every texel, unoccluded (nothing for a
    // Phong-family ks of 0, as the kernel).
    const bool principled = point.specular_model == SpecularModel::principled;
    if (principled || point.ks != glm::dvec3(0.0))
      (principled ? principled_specular : specular) += reference_environment_specular(world, reference_map(world), point, v);
  }
  if (point.specular_model == SpecularModel::principled) {
    // Area lights and the environment: Lambert's irradiance times the diffuse colour (v2's under its
    // dielectric layer), as the kernel (docs/shading.md); v1's highlights from area lights and the
    // environment are in principled_specular.
    const glm::dvec3 weight =
        point.principled.version == 2
            ? reference_principled_v2_lambert(point.principled, std::clamp(glm::dot(n, v), 0.0, 1.0))
            : point.principled.base_color * (1.0 - point.principled.metallic);
    terms.diffuse = principled_diffuse + product(weight, diffuse);
    terms.specular = principled_specular;
    return terms;
  }
  terms.diffuse = product(point.kd, diffuse);
  terms.specular = product(point.ks, specular);
  return terms;
}

}  // namespace phongcl
