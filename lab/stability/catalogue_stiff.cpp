// Stiff exponents: x^q for q from 0 to 1e8 at v.r = 1, 1 - 1e-7, 0.5, ~1e-30 and exactly 0.
#include <cmath>
#include <cstdio>

#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {

// Geometry for one target v.r, specular only (ka = kd = 0, ks = 1, one white light), so the
// pixel's value is x^q itself. The eye is at the origin and the normal axis-aligned, so v and n
// are exact; the light sits where float geometry puts v.r closest to the target.
struct Geometry {
  std::string label;
  glm::vec3 position, normal, light;
};

std::vector<Geometry> geometries() {
  // v = n = (0, 0, 1) and to_light = (a, 0, 1): v.r = l.z = 1 / sqrt(1 + a^2).
  const float a_near_one = static_cast<float>(std::sqrt(1.0 / ((1.0 - 1e-7) * (1.0 - 1e-7)) - 1.0));
  const float a_half = static_cast<float>(std::sqrt(3.0));
  // v = (1, 0, 1.25e-30) (normalised: the 1.25e-30 survives), n = (0, 0, 1), l = (0, 0.6, 0.8):
  // r = (0, -0.6, 0.8) and v.r = 0.8 * 1.25e-30 (the exact value is stated in the case's name).
  // With v = (1, 0, 0) instead, v.r is exactly 0 in any arithmetic: r.x = 2 (n.l) n.x - l.x = 0.
  return {
      {"1", {0, 0, -1}, {0, 0, 1}, {0, 0, 0}},
      {"1-1e-7", {0, 0, -1}, {0, 0, 1}, {a_near_one, 0, 0}},
      {"0.5", {0, 0, -1}, {0, 0, 1}, {a_half, 0, 0}},
      {"1e-30", {-1, 0, -1.25e-30f}, {0, 0, 1}, {-1, 3, 4}},
      {"0", {-1, 0, 0}, {0, 0, 1}, {-1, 3, 4}},
  };
}

}  // namespace

std::vector<StabilityCase> stiff_exponent_cases() {
  std::vector<StabilityCase> cases;
  for (const Geometry& g : geometries()) {
    for (double q : {0.0, 1e-3, 0.5, 1.0, 128.0, 1e4, 1e6, 1e8}) {
      StabilityCase c;
      c.group = "stiff exponents";
      c.scene = starting_scene(0.0, 0.0, 1.0, q);
      c.scene.lights.push_back({LightType::point, glm::dvec3(g.light), {}, {1.0, 1.0, 1.0}});
      c.gbuffer = blank_gbuffer(1, 1, "stiff");
      set_surface(c.gbuffer, 0, g.position, g.normal);
      c = complete(std::move(c));
      // v.r of the float geometry, from the oracle at q = 1 (x^1 = x).
      StabilityCase at_q1 = c;
      at_q1.scene.materials[0].shininess = 1.0;
      const long double x = exact_shade_pixel(at_q1.scene, at_q1.gbuffer, 0)[0];
      char exact_x[48];
      std::snprintf(exact_x, sizeof exact_x, "%.10Lg", x);
      c.name = "q=" + number(q) + " v.r=" + g.label;
      c.what = "max(0, v.r)^q with v.r = " + std::string(exact_x) + " (float geometry)" +
               (q == 0 ? "; pow(0, 0) = 1 by definition, so 1 even at v.r = 0" : "");
      // Defined analytically where the geometry makes v.r exact: 1 and 0.
      if (g.label == "1") c.exact = {{1, 1, 1}};
      if (g.label == "0") c.exact = {ExactColor{q == 0 ? 1.0L : 0.0L, q == 0 ? 1.0L : 0.0L, q == 0 ? 1.0L : 0.0L}};
      const double amplification = stiff_amplification(x, q);
      c.expect.double_precision = double_expectation(amplification);
      c.expect.precise = precise_expectation(amplification);
      c.expect.fast = fast_expectation(amplification);
      // Only the 1e-30 geometry stores a value half cannot hold: P.z = 1.25e-30 becomes 0 (warned),
      // so v = (1, 0, 0) and v.r = 0 exactly: the highlight of x^q at x = 1e-30 is lost.
      c.expect.half_storage = half_expectation(
          c.gbuffer, amplification,
          Expectation::finite_only("P.z = 1.25e-30 is below half's range: stored as 0, with a warning").with_warning());
      c.reference = reference_expectation(direct_pow_amplification(x, q));
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

}  // namespace phongcl
