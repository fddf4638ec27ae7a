#pragma once
// One entry of the stability catalogue: a tiny scene and G-buffer, what each precision variant
// must produce, and why. The catalogue is data; run_catalogue (stability/run_catalogue.h) runs it.
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/precision.h"
#include "stability/exact_shade.h"

namespace phongcl {

// What one precision variant must do on a case.
struct Expectation {
  enum class Kind {
    within,       // every value within `relative` of the oracle (relative_error in exact_error.h)
    finite_only,  // the variant makes no accuracy promise here (why says which); no NaN, right background
    refused,      // shade() throws InputError: the variant cannot represent the input
  };
  Kind kind = Kind::within;
  double relative = 0.0;
  bool warns = false;  // ShadeResult::warnings must say something
  std::string why;     // the justification, printed in the report
  // The float kernels compute a light's F = falloff * window * cone before its colour, n.l, the
  // specular factor and kd or ks multiply it, so where F alone exceeds float they give +Inf even
  // when the exact product does not (docs/shading.md "Stiff and extreme inputs"). A case whose values exceed
  // this threshold exactly where F does (overflowing_above) accepts +Inf there.
  long double overflow_above = std::numeric_limits<long double>::infinity();

  static Expectation within(double relative, std::string why) { return {Kind::within, relative, false, std::move(why)}; }
  static Expectation finite_only(std::string why) { return {Kind::finite_only, 0.0, false, std::move(why)}; }
  static Expectation refused(std::string why) { return {Kind::refused, 0.0, false, std::move(why)}; }
  Expectation overflowing_above(long double threshold) const {
    Expectation early = *this;
    early.overflow_above = threshold;
    return early;
  }
  Expectation with_warning() const {
    Expectation warned = *this;
    warned.warns = true;
    return warned;
  }
};

struct VariantExpectations {
  Expectation double_precision, precise, fast, half_storage;
  const Expectation& operator[](Precision precision) const;
};

struct StabilityCase {
  std::string name;   // "stiff q=1e6 v.r=1-1e-7"
  std::string group;  // "stiff exponents", "degenerate vectors", ...
  std::string what;   // the input and the defined result, one line
  Scene scene;
  GBuffer gbuffer;
  // The oracle's value of every pixel (exact_shade_pixel), or a value the case defines
  // analytically (pow(0, 0) = 1, back-facing = 0); the report shows pixel 0's red channel. Read
  // through exact_values(). Where they are costly (quadratures over an emitter, the GGX tables'
  // integrals) a case leaves `exact` empty and sets `oracle`, which exact_values() calls the first time:
  // every test process builds the whole catalogue to name its tests, and computing every case's values
  // there took 5.6 s of each process.
  mutable std::vector<ExactColor> exact;
  std::function<std::vector<ExactColor>()> oracle;
  const std::vector<ExactColor>& exact_values() const {
    if (exact.empty() && oracle) exact = oracle();
    return exact;
  }
  // Relative errors are taken against max(|exact|, abs_floor): 1e-6 of the scene's brightest light
  // or ambient colour, since shading is linear in them (the product's 1e-6 floor at unit lights).
  double abs_floor = 1e-6;
  // Pixels on an edge of the formula (a hard spot cone, a range's end), where rounding may put
  // them on either side: the oracle's values with the edge moved by the kernel's rounding, each
  // way (with_edge in case_builder.h). A value may equal any of them (a step: lit or not) or, on a
  // continuous edge (the window meets 0 smoothly), anything between them. Empty: no edge.
  std::vector<std::vector<ExactColor>> across;
  bool edge_is_step = true;
  std::size_t nonfinite_pixels = 0;  // pixels ShadeResult::counts must report as non-finite
  // Shadow cases: per pixel, per light, whether the light reaches the pixel (decided from the
  // geometry by hand); `exact` leaves out the lights that do not. Empty: no shadows.
  std::vector<std::vector<bool>> lit;
  VariantExpectations expect;
  Expectation reference = Expectation::within(1e-6, "float rounding of the result");  // the double reference
};

}  // namespace phongcl
