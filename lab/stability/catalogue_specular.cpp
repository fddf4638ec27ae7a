// The specular models other than Phong's (whose limits the stiff exponents hold) at theirs: q -> 0,
// q = 1e6 at and near the peak, an eye grazing the surface, and Blinn's half vector undefined.
#include <cmath>
#include <cstdio>

#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {

bool is_blinn(SpecularModel model) {
  return model == SpecularModel::blinn_phong || model == SpecularModel::blinn_phong_normalized;
}

// The lobe's cosine (v.r or n.h) of the float geometry: the oracle at q = 1 with the model's
// classic twin, ks = 1 and nothing else, is x itself.
long double lobe_cosine(const StabilityCase& c, SpecularModel model) {
  StabilityCase at_q1 = c;
  Material& m = at_q1.scene.materials[0];
  m.shininess = 1.0;
  m.kd = m.ka = glm::dvec3(0.0);
  m.ks = glm::dvec3(1.0);
  m.specular_model = is_blinn(model) ? SpecularModel::blinn_phong : SpecularModel::phong;
  return exact_shade_pixel(at_q1.scene, at_q1.gbuffer, 0)[0];
}

// One pixel at P = (0, 0, -1) seen from the eye at the origin, v = (0, 0, 1), under one white light.
StabilityCase specular_pixel(SpecularModel model, double kd, double q, const Light& light, glm::vec3 normal) {
  StabilityCase c;
  c.group = "specular models";
  c.scene = starting_scene(0.0, kd, 1.0, q);
  c.scene.materials[0].specular_model = model;
  c.scene.lights.push_back(light);
  c.gbuffer = blank_gbuffer(1, 1, "specular");
  set_surface(c.gbuffer, 0, {0, 0, -1}, normal);
  return complete(std::move(c));
}

Light point_at(glm::dvec3 position) { return {LightType::point, position, {}, {1.0, 1.0, 1.0}}; }
Light travelling(glm::dvec3 direction) { return {LightType::directional, {}, direction, {1.0, 1.0, 1.0}}; }

// The stiff exponents' bounds, with x the lobe's cosine: every stored value is exact in half.
StabilityCase with_stiff_bounds(StabilityCase c, long double x, double q) {
  const double amplification = stiff_amplification(x, q);
  c.expect = {double_expectation(amplification), precise_expectation(amplification), fast_expectation(amplification),
              half_expectation(c.gbuffer, amplification, Expectation::finite_only("not reached: exact in half"))};
  c.reference = reference_expectation(direct_pow_amplification(x, q));
  return c;
}

std::string cosine_text(long double x) {
  char text[48];
  std::snprintf(text, sizeof text, "%.10Lg", x);
  return text;
}

}  // namespace

std::vector<StabilityCase> specular_model_cases() {
  std::vector<StabilityCase> cases;
  const glm::vec3 n(0, 0, 1);
  for (SpecularModel model : {SpecularModel::phong_normalized, SpecularModel::blinn_phong, SpecularModel::blinn_phong_normalized}) {
    const std::string name = to_string(model);
    const char* lobe = is_blinn(model) ? "n.h" : "v.r";
    // Near the peak: v = n, l = (a, 0, 1) / |.|, so v.r = cos t and n.h = cos(t / 2), t = atan(a).
    const double t_near = is_blinn(model) ? 2.0 * std::acos(1.0 - 1e-7) : std::acos(1.0 - 1e-7);
    const struct {
      std::string label;
      glm::dvec3 light;
      std::vector<double> exponents;
    } geometries[] = {
        {"1", {0, 0, 0}, {1e6}},
        {"1-1e-7", {static_cast<float>(std::tan(t_near)), 0, 0}, {1e6}},
        {"moderate", {1, 0, 0}, {0.0, 1e-3}},  // t = 45 degrees
    };
    for (const auto& g : geometries) {
      for (double q : g.exponents) {
        StabilityCase c = specular_pixel(model, 0.0, q, point_at(g.light), n);
        const long double x = lobe_cosine(c, model);
        c.name = name + " q=" + number(q) + " " + lobe + "=" + g.label;
        c.what = std::string(lobe) + "^q with " + lobe + " = " + cosine_text(x) + " (float geometry), times the model's " +
                 "factor" + (q == 0 ? "; 0^0 = 1, so the classic lobe is 1 and a normalised one n.l" : "");
        cases.push_back(with_stiff_bounds(std::move(c), x, q));
      }
    }
    // The eye almost in the tangent plane of n = (1, 0, 1e-7), the light in front (n.l = 0.6): the
    // formula, no special case; h = normalize(l + v) stays well defined.
    StabilityCase grazing = specular_pixel(model, 0.5, 8.0, travelling({-0.6, 0, 0.8}), {1, 0, 1e-7f});
    grazing.name = name + " v.n=1e-7";
    grazing.what = "eye almost in the tangent plane: the lobe and its factor as anywhere else";
    grazing.expect = {double_expectation(), precise_expectation(), fast_expectation(),
                      Expectation::within(2e-3, "N.Z = 1e-7 rounds to 2^-11 relative in half: the lobe's cosine moves "
                                                "by ~1e-10, times q = 8; the diffuse part by 5e-4")};
    cases.push_back(std::move(grazing));
    if (is_blinn(model)) {
      // l = (0, 0, -1) = -v, n = (0, 0, -1): lit (n.l = 1), and l + v = 0 exactly: no half vector.
      StabilityCase opposite = specular_pixel(model, 0.5, 8.0, travelling({0, 0, 1}), {0, 0, -1});
      opposite.name = name + " l=-v";
      opposite.what = "light straight behind the point as seen from the eye: l + v = 0 has no half vector, n.h is "
                      "taken as 0, no highlight; diffuse kd n.l = 0.5";
      opposite.exact = {{0.5L, 0.5L, 0.5L}};
      opposite.expect = {double_expectation(), precise_expectation(), fast_expectation(), precise_expectation()};
      opposite.expect.half_storage.why = "every stored value is exact in half: precise's bound";
      cases.push_back(std::move(opposite));
    }
  }
  return cases;
}

}  // namespace phongcl
