// The Principled BSDF v1 (docs/shading.md "Principled"): the kernel against the double reference,
// alone and mixed with Phong's lobe, and the reference's numerical Smith masking against the closed form
// it must integrate to.
#include <cmath>
#include <random>

#include "reference/reference.h"
#include "reference/reference_principled.h"
#include "shading_support.h"

namespace phongcl {
namespace {

using testing::describe_worst;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;

// Measured worst: 2.4e-6 relative on the random materials, 1.5e-5 at roughness 0.1 (alpha^2 = 1e-4: D's
// peak is 1e4 times its floor, so the rounding of n.h and of |n x h|^2 weighs most there). 5e-5 holds it
// with room; a wrong factor (pi, 2, a missing n.l or Fresnel), or 1 - (n.h)^2 computed by cancellation
// (2.8e-3 at roughness 0.1), is off by far more.
constexpr double kPrincipledBound = 5e-5;

std::pair<Scene, GBuffer> principled_scene(unsigned seed, bool mixed) {
  RandomSceneSpec spec;
  auto [scene, gbuffer] = random_scene(spec, seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> zero_one(0.0, 1.0);
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    if (mixed && i % 2 == 1) continue;
    Material& m = scene.materials[i];
    m.specular_model = SpecularModel::principled;
    m.base_color = {zero_one(rng), zero_one(rng), zero_one(rng)};
    m.metallic = i % 3 == 0 ? 1.0 : zero_one(rng) * 0.5;
    m.roughness = 0.1 + 0.9 * zero_one(rng);
    m.specular = zero_one(rng);
    m.specular_tint = zero_one(rng);
  }
  return {scene, gbuffer};
}

TEST(Principled, MatchesTheReferenceAloneAndMixedWithPhong) {
  PHONGCL_REQUIRE_DEVICE(shader);
  unsigned seed = 9100;
  for (bool mixed : {false, true}) {
    for (int lanes : {1, 16}) {
      const auto [scene, gbuffer] = principled_scene(++seed, mixed);
      ShadeOptions options;
      options.lanes = lanes;
      const ShadeResult result = shader.shade(scene, gbuffer, options);
      EXPECT_EQ(result.recipe.value("SPECULAR_MODELS"), mixed ? "17" : "16") << result.build_options;
      const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
      EXPECT_EQ(stats.nonfinite_mismatches, 0u);
      EXPECT_LE(stats.max_rel, kPrincipledBound) << (mixed ? "mixed, " : "alone, ") << lanes << " lanes: " << describe_worst(stats);
    }
  }
}

// The inputs' limits: roughness 0 (a mirror: no highlight from a point), 0.1 and 1, specular 0 (index 1:
// no dielectric reflection) and 3.125 (index 3), metallic 0 and 1, over the random scene's normals, which
// include grazing views and lights. Finite everywhere, and the reference's within the same bound.
TEST(Principled, TheInputsLimitsAreFiniteAndMatchTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  unsigned seed = 9300;
  for (double roughness : {0.0, 0.1, 1.0})
    for (double specular : {0.0, 3.125})
      for (double metallic : {0.0, 1.0}) {
        auto [scene, gbuffer] = principled_scene(++seed, false);
        for (Material& m : scene.materials) m.roughness = roughness, m.specular = specular, m.metallic = metallic;
        const ShadeResult result = shader.shade(scene, gbuffer, ShadeOptions{});
        const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
        EXPECT_EQ(stats.nonfinite_mismatches, 0u);
        EXPECT_LE(stats.max_rel, kPrincipledBound) << "roughness " << roughness << ", specular " << specular << ", metallic "
                                                   << metallic << ": " << describe_worst(stats);
      }
}

// Simpson's rule over the slopes against 2 / (1 + sqrt(1 + alpha^2 tan^2)) (Walter et al. 2007, eq. 34),
// roughness 0.1 to 1 and grazing to normal incidence: the integral is smooth, 1e-9 is its rule's error.
TEST(Principled, TheReferencesNumericalMaskingIsSmithsClosedForm) {
  double worst = 0.0;
  for (double roughness : {0.1, 0.3, 0.6, 1.0})
    for (double mu : {0.01, 0.1, 0.5, 0.9, 0.999}) {
      const double alpha = roughness * roughness, tan_sq = (1.0 - mu * mu) / (mu * mu);
      const double closed = 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan_sq));
      worst = std::max(worst, std::abs(reference_smith_masking(alpha, mu) - closed));
    }
  EXPECT_LE(worst, 1e-9);
}

// Snell's law and the amplitude coefficients give F0 = ((eta - 1) / (eta + 1))^2 at normal incidence and
// total reflection at grazing.
TEST(Principled, TheReferencesFresnelHasItsKnownValues) {
  EXPECT_NEAR(reference_dielectric_fresnel(1.0, 1.5), 0.04, 1e-12);
  EXPECT_NEAR(reference_dielectric_fresnel(1e-9, 1.5), 1.0, 1e-6);
  EXPECT_NEAR(reference_dielectric_fresnel(0.7, 1.0), 0.0, 1e-12);
}

}  // namespace
}  // namespace phongcl
