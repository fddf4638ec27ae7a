#include "stability/case_builder.h"

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace phongcl {

namespace {

constexpr double kFloatUnit = 0x1p-24;
constexpr double kDoubleUnit = 0x1p-53;

double brightest(const Scene& scene) {
  double value = std::max({scene.ambient.x, scene.ambient.y, scene.ambient.z});
  for (const Light& light : scene.lights) value = std::max({value, light.color.x, light.color.y, light.color.z});
  return value;
}

bool exact_in_half(const Plane& plane) {
  return std::all_of(plane.begin(), plane.end(), [](float x) { return !std::isfinite(x) || float(Imath::half(x)) == x; });
}

// Share of the value left above the absolute floor: below 1e-6 the error is measured against the
// floor, so an amplified relative error there shrinks with the value.
double above_floor(long double value) { return static_cast<double>(std::min<long double>(1, value / 1e-6L)); }

}  // namespace

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

Scene starting_scene(double ka, double kd, double ks, double shininess) {
  Scene scene;
  scene.camera.eye = {0.0, 0.0, 0.0};
  scene.materials.push_back({"case material", glm::dvec3(ka), glm::dvec3(kd), glm::dvec3(ks), shininess});
  return scene;
}

StabilityCase complete(StabilityCase c) {
  if (c.exact.empty() && !c.oracle) {
    for (std::size_t i = 0; i < c.gbuffer.pixel_count(); ++i) c.exact.push_back(exact_shade_pixel(c.scene, c.gbuffer, i));
  }
  const double floor = 1e-6 * brightest(c.scene);
  if (floor > 0.0) c.abs_floor = std::min(c.abs_floor, floor);
  return c;
}

StabilityCase with_edge(StabilityCase c, const std::vector<Scene>& moved, bool step) {
  for (const Scene& scene : moved) {
    std::vector<ExactColor> values;
    for (std::size_t i = 0; i < c.gbuffer.pixel_count(); ++i) values.push_back(exact_shade_pixel(scene, c.gbuffer, i));
    c.across.push_back(std::move(values));
  }
  c.edge_is_step = step;
  return c;
}

Expectation reference_expectation(double direct_amplification) {
  return Expectation::within(1e-6 + 16 * kDoubleUnit * direct_amplification, "float result rounding; pow of v.r directly");
}

Expectation double_expectation(double amplification, double packing_amplification) {
  return Expectation::within(1e-6 + 16 * kDoubleUnit * amplification + 16 * kFloatUnit * packing_amplification,
                             "result rounding; float packing of the inputs, times its amplification");
}

Expectation precise_expectation(double amplification) {
  return Expectation::within(1e-5 + 16 * kFloatUnit * amplification, "~30 float roundings, times the amplification");
}

Expectation fast_expectation(double amplification) {
  return Expectation::within(1e-4 + 16 * kFloatUnit * amplification, "relaxed math, times the amplification");
}

Expectation half_expectation(const GBuffer& gbuffer, double amplification, const Expectation& inexact) {
  bool exact = true;
  for (const Planes3* planes : {&gbuffer.position, &gbuffer.normal, &gbuffer.ka, &gbuffer.kd, &gbuffer.ks}) {
    for (const Plane& plane : *planes) exact = exact && exact_in_half(plane);
  }
  exact = exact && exact_in_half(gbuffer.shininess);
  if (!exact) return inexact;
  Expectation same = precise_expectation(amplification);
  same.why = "every stored value is exact in half: precise's bound";
  return same;
}

double stiff_amplification(long double x, double shininess) {
  if (!(x > 0) || shininess == 0) return 1.0;
  const long double per_unit = x < 0.5L ? 1.0L : std::fabs(std::log(x));
  return 1.0 + static_cast<double>(shininess * per_unit) * above_floor(std::pow(x, shininess));
}

double highlight_amplification(double shininess) { return 2.0 * std::sqrt(28.0 * shininess); }

double direct_pow_amplification(long double x, double shininess) {
  if (!(x > 0) || shininess == 0) return 1.0;
  return 1.0 + static_cast<double>(shininess / x) * above_floor(std::pow(x, shininess));
}

}  // namespace phongcl
