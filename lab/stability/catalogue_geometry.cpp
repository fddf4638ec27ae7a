// Grazing and back-facing light, degenerate vectors, scenes far from the origin, lights near surfaces.
#include <cmath>

#include "stability/accuracy_bars.h"
#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {

// One pixel at P with normal N under one directional light travelling along `direction`.
StabilityCase one_pixel(std::string name, std::string group, std::string what, Scene scene, glm::vec3 position,
                        glm::vec3 normal, glm::dvec3 direction, std::size_t nonfinite = 0) {
  StabilityCase c;
  c.name = std::move(name);
  c.group = std::move(group);
  c.what = std::move(what);
  c.scene = std::move(scene);
  c.scene.lights.push_back({LightType::directional, {}, direction, {1.0, 1.0, 1.0}});
  c.gbuffer = blank_gbuffer(1, 1, c.name);
  set_surface(c.gbuffer, 0, position, normal);
  c.nonfinite_pixels = nonfinite;
  return c;
}

// Plain shading, nothing amplified: every variant's base bound, half exact or the given bound.
StabilityCase with_plain_bounds(StabilityCase c, const Expectation& half_inexact) {
  c = complete(std::move(c));
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(), half_expectation(c.gbuffer, 1.0, half_inexact)};
  return c;
}

std::vector<StabilityCase> grazing_cases() {
  const std::string group = "grazing and back-facing";
  // Values of 1e-8 are the point here: a floor far below them, so they are checked relatively.
  auto tiny_floor = [](StabilityCase c) {
    c.abs_floor = 1e-20;
    return c;
  };
  const Scene lit = starting_scene(0.0, 1.0, 1.0, 2.0);
  const Expectation half_na = Expectation::within(1e-5, "exact in half");
  std::vector<StabilityCase> cases;
  // n = (0, 0, 1), l = (1, 0, 1e-8): n.l = 1e-8; r = (-1, 0, 1e-8), v.r = 1e-8: diffuse 1e-8, specular 1e-16.
  cases.push_back(with_plain_bounds(tiny_floor(one_pixel("n.l=1e-8", group, "grazing light: diffuse kd n.l = 1e-8, kept relatively", lit,
                                                         {0, 0, -1}, {0, 0, 1}, {-1, 0, -1e-8})), half_na));
  cases.push_back(with_plain_bounds(tiny_floor(one_pixel("n.l=0", group, "light in the tangent plane: n.l = +0 is not > 0, nothing", lit,
                                                         {0, 0, -1}, {0, 0, 1}, {-1, 0, 0})), half_na));
  // l = -(-1, 0, 0) = (1, -0, -0) and n = (-0, 1, 1)/sqrt 2: every product is -0, so n.l = -0.
  cases.push_back(with_plain_bounds(tiny_floor(one_pixel("n.l=-0", group, "n.l = -0 is not > 0: nothing from the light", lit,
                                                         {0, 0, -1}, {-0.0f, 1, 1}, {-1, 0, 0})), half_na));
  cases.push_back(with_plain_bounds(tiny_floor(one_pixel("n.l=-1e-8", group, "back-facing by 1e-8: nothing from the light", lit,
                                                         {0, 0, -1}, {0, 0, 1}, {-1, 0, 1e-8})), half_na));
  // v = (0, 0, 1) nearly in the tangent plane of n = (1, 0, 1e-7); the light behind the surface
  // as seen from the eye still gives a highlight, v.r = 0.8 + 1.2e-7.
  cases.push_back(with_plain_bounds(one_pixel("v.n=1e-7", group, "eye almost in the tangent plane: the formula, no special case",
                                              starting_scene(0.0, 0.5, 0.5, 8.0), {0, 0, -1}, {1, 0, 1e-7f}, {-0.6, 0, 0.8}),
                                    Expectation::within(2e-3, "N.Z = 1e-7 rounds to 2^-11 relative in half: v.r moves by ~1e-10, "
                                                              "1e-7 n.v by 5e-11; the diffuse part by 5e-4")));
  cases.push_back(with_plain_bounds(one_pixel("eye behind", group, "eye behind the surface (v.n = -1), light in front: the formula "
                                              "has no v.n test, so diffuse n.l, and v.r < 0 gives no highlight",
                                              starting_scene(0.0, 0.5, 0.5, 8.0), {0, 0, -1}, {0, 0, -1}, {-0.6, 0, 0.8}),
                                    half_na));
  return cases;
}

std::vector<StabilityCase> degenerate_cases() {
  const std::string group = "degenerate vectors";
  Scene scene = starting_scene(0.2, 0.5, 0.5, 16.0);
  scene.ambient = {0.1, 0.1, 0.1};
  const glm::dvec3 light{-0.6, 0.0, -0.8};  // l = (0.6, 0, 0.8)
  const Expectation half_rounds = Expectation::within(2e-3, "normal components rounded to half: 2^-11 relative, times q = 16 "
                                                            "at most near v.r = 0.79, ~1e-3");
  std::vector<StabilityCase> cases;
  auto add = [&](std::string name, std::string what, glm::vec3 normal, std::size_t nonfinite = 0) {
    cases.push_back(with_plain_bounds(
        one_pixel(std::move(name), group, std::move(what), scene, {0, 0, -1}, normal, light, nonfinite), half_rounds));
  };
  add("N zero", "zero normal: n = 0, so n.l = 0 and only ambient (ka La) remains", {0, 0, 0});
  add("N denormal 1e-40", "N = (1e-40, 0, 1e-40): squares vanish in float; scaled by a power of two first, a unit vector",
      {1e-40f, 0, 1e-40f});
  add("N huge 1e30", "N = (1e30, 0, 1e30): squares overflow float; scaled by a power of two first, a unit vector",
      {1e30f, 0, 1e30f});
  add("N length 1e-3", "normal of length 1e-3: normalised", {0.6e-3f, 0, 0.8e-3f});
  add("N length 1e3", "normal of length 1e3: normalised", {0.6e3f, 0, 0.8e3f});
  add("N NaN", "NaN in N: the pixel is background, counted as a non-finite normal", {kNaN, 0, 1}, 1);
  add("N Inf", "Inf in N: the pixel is background, counted as a non-finite normal", {0, kInf, 1}, 1);

  StabilityCase light_at_point = one_pixel("light at point", group, "point light at the shaded point: l = 0, n.l = 0, "
                                           "no diffuse or specular from it; ambient remains", scene, {0, 0, -1}, {0, 0, 1}, light);
  light_at_point.scene.lights = {{LightType::point, {0.0, 0.0, -1.0}, {}, {1.0, 1.0, 1.0}}};
  cases.push_back(with_plain_bounds(std::move(light_at_point), half_rounds));
  for (double q : {16.0, 0.0}) {
    StabilityCase eye_at_point = one_pixel(q == 0 ? "eye at point q=0" : "eye at point", group,
                                           q == 0 ? "v = 0, so v.r = 0, and pow(0, 0) = 1: full highlight with q = 0"
                                                  : "eye at the shaded point: v = 0, v.r = 0, no highlight; diffuse remains",
                                           scene, {0, 0, -1}, {0.6f, 0, 0.8f}, light);
    eye_at_point.scene.camera.eye = {0.0, 0.0, -1.0};
    eye_at_point.scene.materials[0].shininess = q;
    cases.push_back(with_plain_bounds(std::move(eye_at_point), half_rounds));
  }
  return cases;
}

std::vector<StabilityCase> far_cases() {
  std::vector<StabilityCase> cases;
  for (double distance : {1e6, 1e7}) {
    auto [scene, gbuffer] = far_from_origin_scene(distance, 11, 4);
    StabilityCase c;
    c.name = "far " + std::string(distance == 1e6 ? "1e6" : "1e7");
    c.group = "far from the origin";
    c.what = "16 random surface points ~" + c.name.substr(4) + " from the origin, eye and lights a few units away, "
             "q up to 1000: positions rebased to the eye in double on the host";
    c.scene = std::move(scene);
    c.gbuffer = std::move(gbuffer);
    c = with_plain_bounds(std::move(c), Expectation::within(
        0.1, "positions relative to the eye (a few units) rounded to half: 2^-11 relative moves v and l by ~5e-4 rad, "
             "times q up to 1000 in the highlight"));
    // Rebased positions and the directional l are rounded to float on the host, the kernel's own
    // vectors carry a few u: direction errors, amplified in highlights of q up to 1000.
    const double amplification = highlight_amplification(1000.0);
    c.expect.double_precision = double_expectation(1.0, amplification);
    c.expect.precise = precise_expectation(amplification);
    c.expect.fast = fast_expectation(amplification);
    cases.push_back(std::move(c));
  }
  return cases;
}

// One point light (quadratic falloff, range 1) a distance D from an eye that is not at the origin,
// and 16 pixels 1e-4 to 1e-1 from it, facing it at 4 angles. L - P is then as small as 1e-8 of
// P - eye, below float's rounding unit: positions and the light relative to the eye, each rounded
// to float, lose it entirely, and the kernel takes both as float pairs (value + rest) instead.
StabilityCase near_light(double distance) {
  StabilityCase c;
  c.name = "light 1e-4 to 0.1 from surfaces " + number(distance) + " away";
  c.group = "lights near surfaces";
  c.what = "point light at " + number(distance) + " from the eye, pixels 1e-4, 1e-3, 1e-2, 0.1 from it: "
           "L - P from positions and the light as float pairs relative to the eye";
  c.scene = starting_scene(0.0, 0.5, 0.5, 8.0);
  c.scene.camera.eye = {0.1, -0.2, 0.3};  // not floats: the positions relative to it have rests
  Light light{LightType::point, c.scene.camera.eye + distance * glm::normalize(glm::dvec3(0.3, -0.2, -1.0)), {},
              {1.0, 1.0, 1.0}};
  light.falloff = Falloff::quadratic;
  light.range = 1.0;
  c.scene.lights.push_back(light);
  c.gbuffer = blank_gbuffer(4, 4, c.name);
  const glm::dvec3 toward_light[4] = {{0.0, 0.0, 1.0}, {0.6, 0.0, 0.8}, {-0.3, 0.5, 0.6}, {0.2, -0.7, 0.3}};
  for (int row = 0; row < 4; ++row) {
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 l = glm::normalize(toward_light[k]);
      const glm::dvec3 position = light.position - std::pow(10.0, row - 4) * l;
      const glm::dvec3 normal = glm::normalize(2.0 * l + glm::normalize(c.scene.camera.eye - position));
      set_surface(c.gbuffer, static_cast<std::size_t>(row * 4 + k), glm::vec3(position), glm::vec3(normal));
    }
  }
  c = complete(std::move(c));
  const double amplification = highlight_amplification(8.0);
  c.expect = {double_expectation(amplification), precise_expectation(amplification), fast_expectation(amplification),
              Expectation::finite_only("half storage keeps 11 bits of a position relative to the eye: no rests")};
  return c;
}

std::vector<StabilityCase> near_light_cases() {
  std::vector<StabilityCase> cases;
  for (double distance : {1.0, 1e2, 1e4}) cases.push_back(near_light(distance));
  return cases;
}

}  // namespace

std::vector<StabilityCase> geometry_cases() {
  std::vector<StabilityCase> cases = grazing_cases();
  for (auto* group : {&degenerate_cases, &far_cases, &near_light_cases}) {
    for (StabilityCase& c : group()) cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace phongcl
