// The stability catalogue (lab/stability), one test per case on every precision variant the
// device runs; no NaN from finite extreme inputs in any variant; the two accuracy bars (far from
// the origin, at the highlight peak) over many pixels. The catalogue's cases carry their own
// tolerances (lab/stability/case_builder.h).
#include <cmath>
#include <limits>
#include <random>

#include "common/error.h"
#include "stability/accuracy_bars.h"
#include "stability/catalogue.h"
#include "stability/exact_error.h"
#include "stability/gbuffer_builder.h"
#include "stability/run_catalogue.h"

#include "shading_support.h"

namespace phongcl {
namespace {

const std::vector<StabilityCase>& catalogue() {
  static const std::vector<StabilityCase> cases = stability_catalogue();
  return cases;
}

class Catalogue : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Catalogue, CasePassesOnEveryVariant) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const StabilityCase& c = catalogue()[GetParam()];
  SCOPED_TRACE(c.name + ": " + c.what);
  // The general kernel: the same formula and code as the specialised one (test_shading checks they
  // agree), in far fewer distinct builds; `phongcl stability` runs the specialised kernels.
  const CaseOutcome outcome = run_case(shader, c, /*specialised=*/false);
  EXPECT_TRUE(outcome.reference_passed) << "reference " << outcome.reference_probe << ", max rel " << outcome.reference_rel;
  for (const VariantOutcome& v : outcome.variants) {
    EXPECT_TRUE(v.passed) << to_string(v.precision) << ": " << v.problem << "; value " << v.probe << ", exact "
                          << static_cast<double>(outcome.exact_probe) << ", max rel " << v.max_rel << " (tolerance "
                          << v.tolerance << ")";
  }
}

std::string case_test_name(const ::testing::TestParamInfo<std::size_t>& info) {
  std::string name = std::to_string(info.param) + "_" + catalogue()[info.param].name;
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Stability, Catalogue, ::testing::Range<std::size_t>(0, catalogue().size()), case_test_name);

// The light-shape cases reach what they are for: each quadratic and cubic falloff sweep has pixels
// where 1/d^k exceeds float (exact values above Li * FLT_MAX) and pixels where it does not, and a
// zero green channel throughout; each case on a hard spot edge or a range's end has a pixel that
// the edge's rounding can move (an admitted value other than the oracle's), or it tests no edge.
TEST(Stability, LightShapeCasesCrossTheirEdges) {
  std::size_t sweeps = 0, edges = 0;
  for (const StabilityCase& c : catalogue()) {
    if (!c.across.empty()) {
      ++edges;
      bool moved = false;
      for (const std::vector<ExactColor>& values : c.across)
        for (std::size_t pixel = 0; pixel < values.size(); ++pixel) moved |= values[pixel] != c.exact_values()[pixel];
      EXPECT_TRUE(moved) << c.name << ": no pixel lies where the edge's rounding changes its value";
    }
    if (c.group != "falloff over distance" || c.scene.lights[0].falloff == Falloff::linear) continue;
    ++sweeps;
    std::size_t overflowing = 0, finite = 0, green = 0;
    for (const ExactColor& value : c.exact_values()) {
      (value[0] > c.expect.precise.overflow_above ? overflowing : finite) += 1;
      green += value[1] != 0;
    }
    EXPECT_GT(overflowing, 0u) << c.name;
    EXPECT_GT(finite, 0u) << c.name;
    EXPECT_EQ(green, 0u) << c.name;
  }
  EXPECT_GT(sweeps, 0u) << "no quadratic or cubic falloff sweep in the catalogue: this test checks nothing";
  EXPECT_GT(edges, 0u) << "no case on an edge of F in the catalogue: this test checks nothing";
}

// Finite but extreme: normals from 1e-45 to 1e38 long (and zero), surfaces from 1e-6 to 1e4 from
// the eye around an eye 1e6 from the origin, q up to 1e30, light colours from 1e-30 to 3e38, point
// lights at the shaded points and 1e30 away, grazing directional lights.
std::pair<Scene, GBuffer> extreme_scene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);
  auto magnitude = [&](double low_exponent, double high_exponent) {
    return std::pow(10.0, low_exponent + (high_exponent - low_exponent) * zero_one(rng));
  };
  auto direction = [&] { return glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)) + glm::dvec3(1e-9)); };

  Scene scene;
  scene.camera.eye = glm::dvec3(1e6, -2e6, 5e5) + direction();
  scene.ambient = glm::dvec3(magnitude(-30, 38));
  for (int i = 0; i < 3; ++i) {
    scene.lights.push_back({LightType::point, scene.camera.eye + direction() * magnitude(-3, 30), {}, glm::dvec3(magnitude(-30, 38))});
    scene.lights.push_back({LightType::directional, {}, direction(), glm::dvec3(magnitude(-30, 38))});
  }
  scene.lights.push_back({LightType::directional, {}, {1.0, 0.0, 1e-8}, glm::dvec3(3e38)});  // grazing for +z normals
  scene.materials.push_back({"table", glm::dvec3(0.1), glm::dvec3(0.5), glm::dvec3(0.5), 1e30});

  GBuffer gbuffer = blank_gbuffer(23, 19, "extreme-" + std::to_string(seed));
  add_per_pixel_materials(gbuffer);
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    const glm::dvec3 position = scene.camera.eye + direction() * magnitude(-6, 4);
    glm::dvec3 normal = direction() * magnitude(-45, 38);
    if (i % 11 == 0) normal = glm::dvec3(0.0);
    if (i % 13 == 0) normal = {0.0, 0.0, 1.0};
    if (i % 17 == 0) scene.lights[0].position = position;  // a light exactly at one shaded point
    set_surface(gbuffer, i, glm::vec3(position), glm::vec3(normal));
    const float shininess = i % 7 == 0 ? 0.0f : static_cast<float>(magnitude(-3, 30));
    set_material(gbuffer, i, static_cast<float>(zero_one(rng)), static_cast<float>(zero_one(rng)),
                 static_cast<float>(zero_one(rng)), shininess);
  }
  return {scene, gbuffer};
}

TEST(Stability, NoNaNFromFiniteExtremeInputsInAnyVariant) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const auto [scene, gbuffer] = extreme_scene(seed);
    for (Precision precision : all_precisions()) {
      if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
      SCOPED_TRACE("seed " + std::to_string(seed) + ", " + to_string(precision));
      ShadeResult result;
      try {
        result = shader.shade(scene, gbuffer, {precision, false});
      } catch (const InputError& error) {
        // half-storage refuses what half cannot hold (q up to 1e30): a clear error, not a NaN.
        EXPECT_EQ(precision, Precision::half_storage) << error.what();
        continue;
      }
      std::size_t nans = 0;
      for (float value : result.image.rgba) nans += std::isnan(value);
      EXPECT_EQ(nans, 0u);
      EXPECT_EQ(result.counts.shaded, gbuffer.pixel_count());
    }
  }
}

// The default precision within kBarRelative of the long double oracle, measured against
// max(|exact|, kBarAbsolute), on every pixel of several 64x64 G-buffers for each bar.
void expect_bar(PhongShader& shader, const char* bar, std::pair<Scene, GBuffer> (*make)(unsigned, int)) {
  for (unsigned seed = 101; seed <= 103; ++seed) {
    const auto [scene, gbuffer] = make(seed, 64);
    const ShadeResult result = shader.shade(scene, gbuffer, {});
    const ExactComparison c = compare_with_exact(result.image, scene, gbuffer, kBarAbsolute);
    EXPECT_EQ(c.nan_values + c.background_mismatches, 0u) << bar << ", seed " << seed;
    EXPECT_LE(c.max_rel, kBarRelative) << bar << ", seed " << seed << ": pixel " << c.worst_pixel << " channel "
                                       << c.worst_channel << " = " << c.worst_value << ", exact "
                                       << static_cast<double>(c.worst_exact);
  }
}

TEST(AccuracyBars, FarFromTheOrigin) {
  PHONGCL_REQUIRE_DEVICE(shader);
  expect_bar(shader, "1e6 from the origin", [](unsigned seed, int size) { return far_from_origin_scene(1e6, seed, size); });
  expect_bar(shader, "1e7 from the origin", [](unsigned seed, int size) { return far_from_origin_scene(1e7, seed, size); });
}

TEST(AccuracyBars, HighlightPeak) {
  PHONGCL_REQUIRE_DEVICE(shader);
  expect_bar(shader, "highlight peak, q 1e2 to 1e6", &highlight_peak_scene);
}

}  // namespace
}  // namespace phongcl
