// HDR colours, half-storage range, many lights, and non-finite input pixels.
#include <cmath>
#include <random>

#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {

// The surface faces the eye and the light shines straight down its normal: n.l = v.r = 1, so the
// value is sum over lights of colour * (kd + ks) + ka La; every stored value is exact in half.
StabilityCase head_on(std::string name, std::string group, std::string what, double kd_and_ks,
                      const std::vector<glm::dvec3>& light_colors, double ka = 0.0, double ambient = 0.0) {
  StabilityCase c;
  c.name = std::move(name);
  c.group = std::move(group);
  c.what = std::move(what);
  c.scene = starting_scene(ka, kd_and_ks, kd_and_ks, 16.0);
  c.scene.ambient = glm::dvec3(ambient);
  for (const glm::dvec3& color : light_colors) c.scene.lights.push_back({LightType::directional, {}, {0, 0, -1}, color});
  c.gbuffer = blank_gbuffer(1, 1, c.name);
  set_surface(c.gbuffer, 0, {0, 0, -1}, {0, 0, 1});
  c = complete(std::move(c));
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(), precise_expectation()};
  c.expect.half_storage.why = "every stored value is exact in half: precise's bound";
  return c;
}

std::vector<StabilityCase> hdr_cases() {
  const std::string group = "HDR and range";
  const glm::dvec3 grey(1.0);
  return {
      head_on("light 1e-30", group, "light colour 1e-30: result 1e-30, scaled by 2^e on the host, not flushed", 0.5, {grey * 1e-30}),
      head_on("light 1e30", group, "light colour 1e30: result 1e30", 0.5, {grey * 1e30}),
      head_on("two lights 3e38", group, "two lights of 3e38, kd = ks = 0.125: their sum 6e38 would overflow float, "
              "the result 1.5e38 does not: finite", 0.125, {grey * 3e38, grey * 3e38}),
      head_on("light 3e38 overflow", group, "light 3e38, kd = ks = 1: the exact result 6e38 overflows float: +Inf", 1.0,
              {grey * 3e38}),
      head_on("ambient+light 3e38", group, "ambient 3e38 (ka 0.5) and a light 3e38 (kd = ks = 0.25): 3e38, finite", 0.25,
              {grey * 3e38}, 0.5, 3e38),
  };
}

std::vector<StabilityCase> half_range_cases() {
  const std::string group = "HDR and range";
  std::vector<StabilityCase> cases;
  StabilityCase beyond = head_on("half beyond 65504", group, "P 1e5 from the eye: half-storage refuses with an error naming "
                                 "the plane and pixel; the float variants shade it", 0.5, {glm::dvec3(1.0)});
  set_surface(beyond.gbuffer, 0, {0, 0, -1e5f}, {0, 0, 1});
  beyond.exact.clear();
  beyond = complete(std::move(beyond));
  beyond.expect.half_storage = Expectation::refused("a value beyond 65504 cannot be stored in half");
  cases.push_back(std::move(beyond));

  StabilityCase below = head_on("half below 6e-8", group, "P.X = 1e-9, below half's smallest subnormal: stored as 0 with "
                                "a warning; the result moves by ~1e-18", 0.5, {glm::dvec3(1.0)});
  set_surface(below.gbuffer, 0, {1e-9f, 0, -1}, {0, 0, 1});
  below.exact.clear();
  below = complete(std::move(below));
  below.expect.half_storage = precise_expectation().with_warning();
  below.expect.half_storage.why = "the flushed 1e-9 changes v by 1e-9 only; a warning is required";
  cases.push_back(std::move(below));
  return cases;
}

// 10,000 lights. Random: directions over the hemisphere, colours log-uniform over 1e-3 to 1e3.
// Adversarial for plain summation: one light of 1 first, then 9,999 of 3e-8 each, each below half
// a float unit of the running sum, so a plain float sum drops every one of them (3e-4 in all).
std::vector<StabilityCase> many_light_cases() {
  const std::string group = "many lights";
  std::vector<StabilityCase> cases;
  cases.push_back(head_on("0 lights", group, "no lights: ambient ka La only", 0.5, {}, 0.2, 0.1));

  StabilityCase mixed;
  mixed.name = "10000 lights mixed";
  mixed.group = group;
  mixed.what = "10,000 point and directional lights, colours log-uniform over 1e-3 to 1e3, q = 16, 4 pixels";
  mixed.scene = starting_scene(0.1, 0.5, 0.5, 16.0);
  mixed.scene.ambient = {0.1, 0.1, 0.1};
  std::mt19937 rng(10000);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-3.0, 3.0);
  for (int i = 0; i < 10000; ++i) {
    const glm::dvec3 color(std::pow(10.0, exponent(rng)), std::pow(10.0, exponent(rng)), std::pow(10.0, exponent(rng)));
    const glm::dvec3 somewhere(unit(rng), unit(rng), unit(rng) + 0.5);
    if (i % 2) mixed.scene.lights.push_back({LightType::point, 5.0 * somewhere, {}, color});
    else mixed.scene.lights.push_back({LightType::directional, {}, -somewhere, color});
  }
  mixed.gbuffer = blank_gbuffer(2, 2, mixed.name);
  const glm::vec3 normals[] = {{0, 0, 1}, {0.6f, 0, 0.8f}, {0, -0.6f, 0.8f}, {0.48f, 0.6f, 0.64f}};
  for (std::size_t i = 0; i < 4; ++i) set_surface(mixed.gbuffer, i, {0, 0, -2}, normals[i]);
  mixed = complete(std::move(mixed));
  // The sum's error is the kernel's concern here; each term keeps precise's per-light bound.
  mixed.expect = {double_expectation(), precise_expectation(), fast_expectation(), half_expectation(mixed.gbuffer, 1.0, Expectation::within(1e-2, "normals rounded to half (2^-11), times q = 16 in the highlights"))};
  cases.push_back(std::move(mixed));

  std::vector<glm::dvec3> colors(10000, glm::dvec3(3e-8));
  colors[0] = glm::dvec3(1.0);
  StabilityCase adversarial = head_on("10000 lights 1 then 3e-8", group, "one light of 1 then 9,999 of 3e-8: a plain float "
                                      "sum drops all of the small ones (3e-4 relative)", 0.5, colors);
  adversarial.expect.fast = Expectation::within(
      5e-4, "-cl-fast-relaxed-math may remove the kernel's compensated summation: plain float's 3e-4 allowed");
  cases.push_back(std::move(adversarial));
  return cases;
}

// One good pixel and one of each non-finite input: those become background and are counted, the
// good one is shaded, the run goes on.
StabilityCase nonfinite_case() {
  StabilityCase c;
  c.name = "non-finite pixels";
  c.group = "non-finite input pixels";
  c.what = "NaN/Inf in P, N, material, per-pixel Kd and shininess: background, counted (7), the finite pixel shaded";
  c.scene = starting_scene(0.0, 0.0, 0.0, 1.0);
  c.scene.ambient = {0.1, 0.1, 0.1};
  c.scene.background = {0.25, 0.5, 0.75};
  c.scene.lights.push_back({LightType::directional, {}, {0, 0, -1}, {1, 1, 1}});
  c.gbuffer = blank_gbuffer(8, 1, c.name);
  add_per_pixel_materials(c.gbuffer);
  for (std::size_t i = 0; i < 8; ++i) {
    set_surface(c.gbuffer, i, {0, 0, -1}, {0, 0, 1});
    set_material(c.gbuffer, i, 0.5f, 0.5f, 0.5f, 8.0f);
  }
  c.gbuffer.position[0][1] = kNaN;
  c.gbuffer.position[2][2] = -kInf;
  c.gbuffer.normal[1][3] = kNaN;
  c.gbuffer.normal[2][4] = kInf;
  c.gbuffer.material[5] = kNaN;
  c.gbuffer.kd[1][6] = kNaN;
  c.gbuffer.shininess[7] = kInf;
  c.nonfinite_pixels = 7;
  c = complete(std::move(c));
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(), precise_expectation()};
  c.expect.half_storage.why = "every stored finite value is exact in half: precise's bound";
  return c;
}

}  // namespace

std::vector<StabilityCase> range_cases() {
  std::vector<StabilityCase> cases = hdr_cases();
  for (auto* group : {&half_range_cases, &many_light_cases}) {
    for (StabilityCase& c : group()) cases.push_back(std::move(c));
  }
  cases.push_back(nonfinite_case());
  return cases;
}

}  // namespace phongcl
