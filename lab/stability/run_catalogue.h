#pragma once
// Runs stability cases through the real pipeline (PhongShader::shade, every precision variant the
// device supports, unculled and, with point or spot lights, with tiled light culling) and the
// double reference, and judges each against its expectations.
#include <string>
#include <vector>

#include "shading/phong_shader.h"
#include "stability/stability_case.h"

namespace phongcl {

struct VariantOutcome {
  Precision precision = Precision::precise;
  bool supported = true;  // false: the device cannot run it (double without fp64), not run
  bool passed = false;
  Expectation::Kind expected = Expectation::Kind::within;
  double tolerance = 0.0;
  double max_rel = 0.0;      // over every shaded value of the case
  float probe = 0.0f;        // pixel 0, red
  std::string problem;       // why it failed; for a refusal, the message the user would see
};

struct CaseOutcome {
  std::string name, group, what;
  long double exact_probe = 0;  // pixel 0, red
  float reference_probe = 0.0f;
  double reference_rel = 0.0;
  bool reference_passed = false;
  std::vector<VariantOutcome> variants;  // in all_precisions() order
  bool passed() const;
};

// specialised: the kernel the recipe specialises (the product's default) or the general one
// (same formula and code, fewer distinct builds: what the test suite uses to stay quick).
CaseOutcome run_case(PhongShader& shader, const StabilityCase& stability_case, bool specialised = true);

struct StabilityRun {
  std::string device;
  std::vector<CaseOutcome> cases;
  std::size_t failures() const;
};

StabilityRun run_catalogue(PhongShader& shader, const std::vector<StabilityCase>& catalogue, bool specialised = true);

}  // namespace phongcl
