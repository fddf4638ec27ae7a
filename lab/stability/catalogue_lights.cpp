// Light shapes: falloff over forty decades of distance, range windows at their end, spot cones
// from 1e-3 to 179.999 degrees with hard and wide soft edges, light linking at mask word boundaries.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {


// Every light of these cases sits at the eye (the origin) and every pixel faces it: v = l = n, so
// n.l = v.r = 1 exactly and a value is Li (kd + ks) F, F = falloff(d) * window(d) * cone(l).
Light light_at_eye(LightType type, double brightness, Falloff falloff = Falloff::none) {
  Light light;
  light.type = type;
  light.position = glm::dvec3(0.0);
  light.direction = {0.0, 0.0, -1.0};  // a spot points down -z
  light.color = glm::dvec3(brightness);
  light.falloff = falloff;
  return light;
}

void set_facing(GBuffer& gbuffer, std::size_t index, const glm::vec3& position, float material = 0.0f) {
  set_surface(gbuffer, index, position, -position, material);
}

// Where a value is Li F (kd + ks = 1, n.l = v.r = 1), F exceeds float exactly where the value
// exceeds Li * FLT_MAX: the float variants may give +Inf there (Expectation::overflow_above).
// The double variant holds 1/d^3 of any float d.
void allow_early_overflow(StabilityCase& c, double brightness) {
  const long double threshold = brightness * static_cast<long double>(std::numeric_limits<float>::max());
  for (Expectation* float_variant : {&c.expect.precise, &c.expect.fast}) {
    *float_variant = float_variant->overflowing_above(threshold);
    float_variant->why += "; +Inf where F alone exceeds float";
  }
}

// --- Falloff: one pixel per decade, d = 10^e for e = -20..20 along -z; three rows of materials:
// kd = ks = 0.5, then kd = 0 (ks = 1), then ks = 0 (kd = 1), and the light's green is 0: a zero
// factor takes nothing even from an infinite 1/d^k.
constexpr int kFirstDecade = -20, kDecades = 41;

StabilityCase falloff_sweep(Falloff falloff, double brightness) {
  StabilityCase c;
  c.name = std::string(to_string(falloff)) + " Li=" + number(brightness);
  c.group = "falloff over distance";
  c.scene = starting_scene(0.0, 0.0, 0.0, 16.0);
  Light light = light_at_eye(LightType::point, brightness, falloff);
  light.color.g = 0.0;
  c.scene.lights.push_back(light);
  c.gbuffer = blank_gbuffer(kDecades, 3, c.name);
  add_per_pixel_materials(c.gbuffer);
  const float coefficients[3][2] = {{0.5f, 0.5f}, {0.0f, 1.0f}, {1.0f, 0.0f}};
  for (int row = 0; row < 3; ++row) {
    for (int k = 0; k < kDecades; ++k) {
      const std::size_t i = static_cast<std::size_t>(row * kDecades + k);
      set_facing(c.gbuffer, i, {0.0f, 0.0f, -static_cast<float>(std::pow(10.0L, kFirstDecade + k))});
      set_material(c.gbuffer, i, 0.0f, coefficients[row][0], coefficients[row][1], 16.0f);
    }
  }
  c = complete(std::move(c));
  int overflowing = 0;
  for (const ExactColor& value : c.exact) overflowing += std::isinf(static_cast<float>(value[0]));
  c.what = "Li (1, 0, 1) = " + number(brightness) + " / d^" + std::to_string(static_cast<int>(falloff)) +
           ", d = 1e-20 to 1e20 by decades, kd/ks 0.5/0.5, 0/1, 1/0: " + std::to_string(overflowing) +
           " of 123 red values exceed float (+Inf), green 0 everywhere";
  // v = l = n exactly: only 1/d (rsqrt, 2 ulp) and its k products round; every variant's base bound.
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(),
              Expectation::refused("d = 1e5 to 1e20 exceeds half's 65504")};
  allow_early_overflow(c, brightness);
  return c;
}

std::vector<StabilityCase> falloff_cases() {
  // Brightnesses that put the overflow inside the sweep (1 / d^k > 3.4e38 / Li), and a dim light
  // whose results stay finite where 1 / d^k alone would not.
  std::vector<StabilityCase> cases;
  for (auto [falloff, brightness] : {std::pair{Falloff::linear, 1e20}, {Falloff::linear, 1e-30}, {Falloff::quadratic, 1.0},
                                     {Falloff::quadratic, 1e-30}, {Falloff::cubic, 1.0}, {Falloff::cubic, 1e-30}}) {
    cases.push_back(falloff_sweep(falloff, brightness));
  }
  return cases;
}

// --- Range: rows of pixels at d = R/2, R(1 - 2^-4), one float below R, R itself, one float
// above, R(1 + 2^-4) and 2R along -z, R a float so that one pixel is exactly at it. Li = R^k keeps
// the unwindowed value near 1. A row is 16 pixels, so a work-item of up to 16 lanes holds one
// distance only (no background lane to hide a tiled kernel's skipping a light that reaches it).
StabilityCase range_row(float range, Falloff falloff) {
  StabilityCase c;
  const int power = static_cast<int>(falloff);
  c.name = "range R=" + number(range) + (power ? " " + std::string(to_string(falloff)) : "");
  c.group = "range window";
  c.what = "window (1 - (d/R)^4)^2 at d = R/2, R(1 -+ 2^-4), R and its float neighbours, 2R" +
           std::string(power ? ", Li = R^k / d^k" : "") + ": 0 at and beyond R";
  c.scene = starting_scene(0.0, 0.5, 0.5, 16.0);
  Light light = light_at_eye(LightType::point, std::pow(static_cast<double>(range), power), falloff);
  light.range = range;
  c.scene.lights.push_back(light);
  const float distances[] = {range / 2, range * (1 - 0x1p-4f), std::nextafter(range, 0.0f), range,
                             std::nextafter(range, 2 * range), range * (1 + 0x1p-4f), 2 * range};
  constexpr int kRow = 16;
  c.gbuffer = blank_gbuffer(kRow, 7, c.name);
  for (std::size_t i = 0; i < c.gbuffer.pixel_count(); ++i) set_facing(c.gbuffer, i, {0.0f, 0.0f, -distances[i / kRow]});
  c = complete(std::move(c));
  // The pixels at R and one float either side are on the window's end within d / R's rounding;
  // the window meets 0 with zero slope, so anything between the moved edges' values passes.
  std::vector<Scene> moved(2, c.scene);
  moved[0].lights[0].range *= 1 - kEdgeRelative;
  moved[1].lights[0].range *= 1 + kEdgeRelative;
  c = with_edge(std::move(c), moved, /*step=*/false);
  const Expectation half = range > 65504.0f ? Expectation::refused("d beyond 65504 cannot be stored in half")
                           : range < 1e-4f  ? Expectation::finite_only("P.z below half's 6e-8 is stored as 0, with a "
                                                                        "warning: d = 0, nothing from the light")
                                                  .with_warning()
                                            : Expectation::within(1e-5, "R's float neighbours round to R in half, where "
                                                                        "the window is below 1e-13 anyway");
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(), half};
  allow_early_overflow(c, light.color.r);
  return c;
}

std::vector<StabilityCase> range_cases_of_window() {
  std::vector<StabilityCase> cases;
  for (float range : {1e-20f, 1.0f, 1e20f}) cases.push_back(range_row(range, Falloff::none));
  for (float range : {1e-20f, 1e20f}) cases.push_back(range_row(range, Falloff::quadratic));
  return cases;
}

// --- Spot cones. Pixels on the unit sphere around the spot at angles theta from its axis, each
// facing it: a value is Li (kd + ks) window(1) cone(theta). The range, 1 + 2^-4, puts every pixel
// near the end of the cone's culling sphere (narrow: through apex and rim; wide: the rim's circle),
// which tiled culling must not cut (window(1) = 0.046).
constexpr double kSpotRange = 1.0625;
// The window's relative change per relative change of d there: |d ln W / d ln d| = 8 x^4 / (1 - x^4).
double spot_window_amplification() {
  const double x4 = std::pow(1.0 / kSpotRange, 4.0);
  return 8.0 * x4 / (1.0 - x4);
}

glm::vec3 on_sphere(long double theta) {
  return {static_cast<float>(std::sin(theta)), 0.0f, static_cast<float>(-std::cos(theta))};
}

long double angle_of(const glm::vec3& p) { return std::atan2(static_cast<long double>(p.x), -static_cast<long double>(p.z)); }

double degrees(long double radians) { return static_cast<double>(radians * 180 / std::numbers::pi_v<long double>); }

StabilityCase spot_case(std::string name, std::string what, double cone_deg, double penumbra_deg,
                        const std::vector<glm::vec3>& pixels, double cosine_power = 0.0) {
  StabilityCase c;
  c.name = std::move(name);
  c.group = "spot cones";
  c.what = std::move(what);
  c.scene = starting_scene(0.0, 0.5, 0.5, 16.0);
  Light spot = light_at_eye(LightType::spot, 1.0);
  spot.cone_angle_deg = cone_deg;
  spot.penumbra_angle_deg = penumbra_deg;
  spot.cosine_power = cosine_power;
  spot.range = kSpotRange;
  c.scene.lights.push_back(spot);
  c.gbuffer = blank_gbuffer(static_cast<int>(pixels.size()), 1, c.name);
  for (std::size_t i = 0; i < pixels.size(); ++i) set_facing(c.gbuffer, i, pixels[i]);
  return complete(std::move(c));
}

// The oracle with the spot's cone turned wider and narrower by the kernel's rounding of the
// off-axis angle at `theta` (kEdgeRelative, kEdgeAbsolute).
std::vector<Scene> cones_moved(const Scene& scene, long double theta) {
  const long double rounding = theta * kEdgeRelative + kEdgeAbsolute;
  const Light& spot = scene.lights[0];
  const long double inner = spot.cone_angle_deg / 2 * std::numbers::pi_v<long double> / 180;
  std::vector<Scene> moved(2, scene);
  moved[0].lights[0].cone_angle_deg = 2 * degrees(std::max(0.0L, inner - rounding));
  moved[1].lights[0].cone_angle_deg = 2 * degrees(inner + rounding);
  return moved;
}

// P = 0. The edge runs through a float pixel: A is twice that pixel's exact angle, so which side
// it is on is decided by A's double rounding. It, its neighbours one float away (in the component
// that moves the angle most) and any pixel within the edge's rounding may come out lit or unlit,
// but nothing between (a step); the axis, theta / 2, theta (1 -+ 2^-4) and a pixel well outside
// must match the oracle's side.
StabilityCase hard_spot(double cone_deg) {
  const glm::vec3 edge = on_sphere(cone_deg / 2 * std::numbers::pi_v<long double> / 180);
  const long double half_angle = angle_of(edge);
  const bool x_moves_more = std::fabs(edge.x) < std::fabs(edge.z);
  glm::vec3 below = edge, above = edge;
  float& below_component = x_moves_more ? below.x : below.z;
  float& above_component = x_moves_more ? above.x : above.z;
  below_component = std::nextafter(below_component, -1.0f);
  above_component = std::nextafter(above_component, 1.0f);
  const std::vector<glm::vec3> pixels = {on_sphere(0),
                                         on_sphere(half_angle / 2),
                                         on_sphere(half_angle * (1 - 0x1p-4L)),
                                         below,
                                         edge,
                                         above,
                                         on_sphere(half_angle * (1 + 0x1p-4L)),
                                         on_sphere((half_angle + std::numbers::pi_v<long double>) / 2)};
  StabilityCase c = spot_case("hard A=" + number(cone_deg), "spot of A = " + number(cone_deg) + " degrees, P = 0: "
                              "lit inside, 0 outside; the pixel on the edge and its float neighbours lit or 0, "
                              "nothing between", 2 * degrees(half_angle), 0.0, pixels);
  const std::vector<Scene> moved = cones_moved(c.scene, half_angle);  // before c is moved from
  c = with_edge(std::move(c), moved, /*step=*/true);
  // d's few rounding units, times the window's amplification at d/R = 0.94.
  const double window = spot_window_amplification();
  c.expect = {double_expectation(), precise_expectation(window), fast_expectation(window),
              Expectation::finite_only("P rounded to half (2^-11) moves theta by ~5e-4 rad, across the edge")};
  return c;
}

// P > 0: the axis, halfway to the inner edge, a quarter, half and three quarters of the way
// through the penumbra, and well outside. The smoothstep is continuous, but over a narrow
// penumbra (1e-3 degrees is 1.7e-5 rad) the angle's rounding (~1e-7 rad) is a fair part of it:
// a value passes between the oracle's values for the cone moved by that rounding (a continuous
// edge), then within the variant's bound for d's rounding times the window's amplification.
StabilityCase soft_spot(double cone_deg, double penumbra_deg) {
  const long double inner = cone_deg / 2 * std::numbers::pi_v<long double> / 180, outer = inner + penumbra_deg * std::numbers::pi_v<long double> / 180;
  std::vector<glm::vec3> pixels = {on_sphere(0), on_sphere(inner / 2)};
  for (long double t : {0.25L, 0.5L, 0.75L}) pixels.push_back(on_sphere(inner + t * (outer - inner)));
  pixels.push_back(on_sphere((outer + std::numbers::pi_v<long double>) / 2));
  StabilityCase c = spot_case("soft A=" + number(cone_deg) + " P=" + number(penumbra_deg),
                              "spot of A = " + number(cone_deg) + ", P = " + number(penumbra_deg) + " degrees" +
                                  (std::fabs(cone_deg / 2 + penumbra_deg - 90) < 1e-9 ? " (A/2 + P = 90)" : "") +
                                  ": 1 inside, the smoothstep through the penumbra, 0 outside",
                              cone_deg, penumbra_deg, pixels);
  const std::vector<Scene> moved = cones_moved(c.scene, outer);  // before c is moved from
  c = with_edge(std::move(c), moved, /*step=*/false);
  // Half rounds P to 2^-11: theta moves by up to ~5e-4 rad, s by that over the penumbra, and the
  // smoothstep by up to ~7 times s's error, relatively, at a quarter of the way through; d by
  // 2^-11 relative, which the window multiplies by spot_window_amplification() (29).
  const double penumbra_rad = penumbra_deg * static_cast<double>(std::numbers::pi_v<long double>) / 180;
  const Expectation half = penumbra_rad > 0.1 ? Expectation::within(7 * 5e-4 / penumbra_rad + 0x1p-11 * spot_window_amplification(),
                                                                    "P rounded to half: theta moves ~5e-4 rad, the smoothstep "
                                                                    "7 times that over P; d 2^-11, times the window's 29")
                                              : Expectation::finite_only("P rounded to half moves theta by ~5e-4 rad, "
                                                                         "more than the whole penumbra");
  const double window = spot_window_amplification();
  c.expect = {double_expectation(), precise_expectation(window), fast_expectation(window), half};
  return c;
}

// A cosine power p: pixels at angles theta from the axis, inside a hard cone of A degrees, where a
// value is Li (kd + ks) window(1) c^p, c = cos(theta). c^p's relative error is p times the absolute
// error of 1 - c, which is ~3 u of 1 - c (no cancellation) where the kernel takes the logarithm
// from it: an amplification of p (1 - c) / c, counted where c^p is above the absolute floor.
StabilityCase spot_power(double power, double cone_deg, const std::vector<long double>& thetas) {
  std::vector<glm::vec3> pixels;
  double amplification = spot_window_amplification();
  for (long double theta : thetas) {
    pixels.push_back(on_sphere(theta));
    const long double c = std::cos(theta), versine = 1 - c;
    if (std::pow(c, power) > 1e-6L) amplification = std::max(amplification, 1.0 + static_cast<double>(power * versine / c));
  }
  StabilityCase c = spot_case("power p=" + number(power) + " A=" + number(cone_deg),
                              "spot of A = " + number(cone_deg) + " degrees with cosine power " + number(power) +
                                  ": c^p from the axis to theta = " + number(static_cast<double>(thetas.back())) + " rad",
                              cone_deg, 0.0, pixels, power);
  // Positions are packed exactly (the eye at the origin); the double reference takes pow(c, p) with
  // c rounded to 2^-53 absolutely, an amplification of p / c.
  c.expect = {double_expectation(amplification), precise_expectation(amplification), fast_expectation(amplification),
              Expectation::finite_only("half moves theta by ~5e-4 rad, c^p by p theta 5e-4 relative (or 5e-4 / c)")};
  return c;
}

std::vector<StabilityCase> spot_cases() {
  std::vector<StabilityCase> cases;
  for (double cone : {1e-3, 60.0, 179.999}) cases.push_back(hard_spot(cone));
  for (auto [cone, penumbra] : {std::pair{1e-3, 10.0}, {1e-3, 89.9995}, {20.0, 80.0}, {179.998, 0.001}})
    cases.push_back(soft_spot(cone, penumbra));
  // Large p near the axis (c^p from 1 to e^-4.5 within 0.03 rad; p = 1e6 within 3e-3 rad), and p = 1
  // out to grazing, 0.06 degrees inside a cone of 179.8 degrees (c = 2.7e-3).
  cases.push_back(spot_power(1e4, 60.0, {0, 1e-4L, 1e-3L, 5e-3L, 1e-2L, 2e-2L, 3e-2L, 0.5L}));
  cases.push_back(spot_power(1e6, 60.0, {0, 1e-5L, 1e-4L, 5e-4L, 1e-3L, 2e-3L, 3e-3L}));
  cases.push_back(spot_power(1.0, 179.8, {0, std::numbers::pi_v<long double> / 4, std::numbers::pi_v<long double> * 80 / 180, std::numbers::pi_v<long double> * 89 / 180, std::numbers::pi_v<long double> * 89.8L / 180, std::numbers::pi_v<long double> * 89.84L / 180}));
  return cases;
}

// --- Light linking: 64 materials, so two mask words; pixels of materials 0, 30, 31, 32, 33, 62
// and 63 under a point light linked to {31, 32, 63} and a directional one of 1/4 linked to {0, 32}.
StabilityCase linking_case() {
  StabilityCase c;
  c.name = "linking words 31|32|63";
  c.group = "light linking";
  c.what = "64 materials (two mask words); a point light linked to 31, 32, 63 and a directional one (1/4) to 0, "
           "32: materials 0, 30, 31, 32, 33, 62, 63 get 1/4, 0, 1, 5/4, 0, 0, 1";
  c.scene = starting_scene(0.0, 0.5, 0.5, 16.0);
  c.scene.materials.resize(64, c.scene.materials[0]);
  Light point = light_at_eye(LightType::point, 1.0);
  point.materials = std::vector<int>{31, 32, 63};
  Light directional = light_at_eye(LightType::directional, 0.25);
  directional.materials = std::vector<int>{0, 32};
  c.scene.lights = {point, directional};
  const float materials[] = {0, 30, 31, 32, 33, 62, 63};
  c.gbuffer = blank_gbuffer(7, 1, c.name);
  for (std::size_t i = 0; i < 7; ++i) set_facing(c.gbuffer, i, {0.0f, 0.0f, -1.0f}, materials[i]);
  c = complete(std::move(c));
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(), precise_expectation()};
  c.expect.half_storage.why = "every stored value is exact in half: precise's bound";
  return c;
}

}  // namespace

std::vector<StabilityCase> light_shape_cases() {
  std::vector<StabilityCase> cases = falloff_cases();
  for (auto* group : {&range_cases_of_window, &spot_cases}) {
    for (StabilityCase& c : group()) cases.push_back(std::move(c));
  }
  cases.push_back(linking_case());
  return cases;
}

}  // namespace phongcl
