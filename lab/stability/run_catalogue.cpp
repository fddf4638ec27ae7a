#include "stability/run_catalogue.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "reference/reference.h"
#include "stability/exact_error.h"

namespace phongcl {

namespace {

// The error of one value against the case: its oracle value, or on an edge (StabilityCase::across)
// the nearest of the values the edge's rounding admits.
double case_error(const StabilityCase& c, float value, std::size_t pixel, int channel) {
  if (c.across.empty()) return relative_error(value, c.exact_values()[pixel][channel], c.abs_floor);
  std::vector<long double> admissible{c.exact_values()[pixel][channel]};
  for (const std::vector<ExactColor>& moved : c.across) admissible.push_back(moved[pixel][channel]);
  return relative_error_to_any(value, admissible, !c.edge_is_step, c.abs_floor);
}

// Judges one image against the case: sets max_rel and returns "" or what is wrong. Every kind of
// expectation forbids NaN and wants background pixels exactly; `within` also bounds the error, and
// `finite_only` wants +-Inf only where the exact value overflows.
std::string judge_image(const Image& image, const StabilityCase& c, const Expectation& expectation, double& max_rel) {
  max_rel = 0.0;
  std::string worst;
  for (std::size_t i = 0; i < c.gbuffer.pixel_count(); ++i) {
    const float* pixel = image.pixel(i);
    const bool shaded = classify_pixel(c.gbuffer, i) == PixelClass::shaded;
    for (int ch = 0; ch < 4; ++ch) {
      if (std::isnan(pixel[ch])) return "NaN at pixel " + std::to_string(i);
    }
    if (!shaded) {
      for (int ch = 0; ch < 3; ++ch) {
        if (pixel[ch] != static_cast<float>(c.scene.background[ch]) || pixel[3] != 0.0f)
          return "pixel " + std::to_string(i) + " should be background";
      }
      continue;
    }
    for (int ch = 0; ch < 3; ++ch) {
      const bool early_overflow = std::isinf(pixel[ch]) && pixel[ch] > 0 && c.exact_values()[i][ch] > expectation.overflow_above;
      const double error = early_overflow ? 0.0 : case_error(c, pixel[ch], i, ch);
      if (expectation.kind == Expectation::Kind::finite_only) {
        if (std::isinf(error)) return "+-Inf where the exact value is finite, at pixel " + std::to_string(i);
        continue;
      }
      if (error > max_rel || (std::isinf(error) && worst.empty())) {
        max_rel = error;
        char text[96];
        std::snprintf(text, sizeof text, " (pixel %zu channel %d: %.7g, exact %.7Lg)", i, ch, pixel[ch], c.exact_values()[i][ch]);
        worst = text;
      }
    }
  }
  if (expectation.kind == Expectation::Kind::within && !(max_rel <= expectation.relative))
    return "error above tolerance" + worst;
  return "";
}

VariantOutcome run_variant(PhongShader& shader, const StabilityCase& c, Precision precision, bool specialised,
                           Culling culling) {
  VariantOutcome outcome;
  outcome.precision = precision;
  const Expectation& expectation = c.expect[precision];
  outcome.expected = expectation.kind;
  outcome.tolerance = expectation.relative;
  if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) {
    outcome.supported = false;
    outcome.passed = true;
    return outcome;
  }
  ShadeResult result;
  try {
    ShadeOptions options{precision, specialised};
    options.culling = culling;
    result = shader.shade(c.scene, c.gbuffer, options);
  } catch (const InputError& error) {
    outcome.problem = error.what();
    outcome.passed = expectation.kind == Expectation::Kind::refused;
    return outcome;
  }
  outcome.probe = result.image.pixel(0)[0];
  if (expectation.kind == Expectation::Kind::refused) {
    outcome.problem = "shaded, but the input should have been refused";
    return outcome;
  }
  outcome.problem = judge_image(result.image, c, expectation, outcome.max_rel);
  const PixelCounts& counts = result.counts;
  const std::size_t nonfinite = counts.nonfinite_position + counts.nonfinite_normal + counts.nonfinite_material;
  if (outcome.problem.empty() && nonfinite != c.nonfinite_pixels) {
    outcome.problem = "counted " + std::to_string(nonfinite) + " non-finite pixels, expected " +
                      std::to_string(c.nonfinite_pixels);
  }
  if (outcome.problem.empty() && expectation.warns && result.warnings.empty()) outcome.problem = "no warning";
  outcome.passed = outcome.problem.empty();
  return outcome;
}

bool has_point_lights(const Scene& scene) {
  return std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& light) { return light.type != LightType::directional; });
}

// A variant without culling and, where the case has point or spot lights, with tiled culling too
// (whose lists must drop only lights that add exactly 0): both must pass; the report shows the
// unculled probe and the larger error.
VariantOutcome run_variant_culled_and_not(PhongShader& shader, const StabilityCase& c, Precision precision, bool specialised) {
  VariantOutcome outcome = run_variant(shader, c, precision, specialised, Culling::none);
  if (!outcome.supported || !has_point_lights(c.scene)) return outcome;
  const VariantOutcome tiled = run_variant(shader, c, precision, specialised, Culling::tiled);
  outcome.max_rel = std::max(outcome.max_rel, tiled.max_rel);
  if (outcome.passed && !tiled.passed) {
    outcome.passed = false;
    outcome.problem = "tiled culling: " + tiled.problem;
  }
  return outcome;
}

}  // namespace

const Expectation& VariantExpectations::operator[](Precision precision) const {
  switch (precision) {
    case Precision::double_precision: return double_precision;
    case Precision::precise: return precise;
    case Precision::fast: return fast;
    case Precision::half_storage: return half_storage;
  }
  return precise;
}

bool CaseOutcome::passed() const {
  return reference_passed && std::all_of(variants.begin(), variants.end(), [](const VariantOutcome& v) { return v.passed; });
}

CaseOutcome run_case(PhongShader& shader, const StabilityCase& c, bool specialised) {
  CaseOutcome outcome;
  outcome.name = c.name;
  outcome.group = c.group;
  outcome.what = c.what;
  outcome.exact_probe = c.exact_values().at(0)[0];
  const Image reference = reference_image(c.scene, c.gbuffer);
  outcome.reference_probe = reference.pixel(0)[0];
  outcome.reference_passed = judge_image(reference, c, c.reference, outcome.reference_rel).empty();
  for (Precision precision : all_precisions())
    outcome.variants.push_back(run_variant_culled_and_not(shader, c, precision, specialised));
  return outcome;
}

std::size_t StabilityRun::failures() const {
  return static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), [](const CaseOutcome& c) { return !c.passed(); }));
}

StabilityRun run_catalogue(PhongShader& shader, const std::vector<StabilityCase>& catalogue, bool specialised) {
  StabilityRun run;
  run.device = describe(shader.compute().device.info);
  for (const StabilityCase& c : catalogue) run.cases.push_back(run_case(shader, c, specialised));
  return run;
}

}  // namespace phongcl
