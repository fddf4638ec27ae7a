// Cycles' Oren-Nayar, version 2's diffuse where Diffuse Roughness > 0 (kernels/oren_nayar.h,
// docs/shading.md "Oren-Nayar"): the reference's integrated albedos against Fujii's closed form, the
// energy it keeps, the kernel against the reference under every light type, and the flag that
// compiles it in.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "area_test_scenes.h"
#include "reference/reference.h"
#include "reference/reference_oren_nayar.h"
#include "shading_support.h"

namespace phongcl {
namespace {

using std::numbers::pi;
using testing::describe_worst;
using testing::shading_error;

// Fujii's G in closed form, as Cycles' bsdf_oren_nayar_G writes it (with its Taylor series below 1e-6).
double fujii_g(double c) {
  if (c < 1e-6) return pi / 2.0 - 2.0 / 3.0 - c;
  const double s = std::sqrt(1.0 - c * c), theta = std::acos(c);
  return s * (theta - 2.0 / 3.0 - s * c) + 2.0 / 3.0 * (s / c) * (1.0 - s * s * s);
}

// The reference integrates E over the hemisphere (Simpson's rule, 2 x 256 intervals: measured 1.1e-10
// from the closed form) and E_avg over E (128 intervals: 3.6e-8, E's square root at c = 1).
TEST(OrenNayar, TheReferencesAlbedosAreFujiisClosedForm) {
  for (double sigma : {1e-5, 0.3, 1.0}) {
    const double a = 1.0 / (pi + sigma * (pi / 2.0 - 2.0 / 3.0)), b = sigma * a;
    for (double c : {0.0, 1e-3, 0.2, 0.5, 0.9, 1.0})
      EXPECT_NEAR(reference_oren_nayar_albedo(sigma, c), a * pi + b * fujii_g(c), 1e-9) << "sigma " << sigma << ", c " << c;
    EXPECT_NEAR(reference_oren_nayar_average(sigma), a * pi + (2.0 * pi - 5.6) / 3.0 * b, 1e-7) << "sigma " << sigma;
  }
}

// OpenPBR's multiple scattering gives back what single scattering loses: a white surface under a white
// world reflects all of it at every roughness and view; a darker one less than Lambert's, except at a
// grazing view, where single scattering alone reflects everything (E(0) = 1).
TEST(OrenNayar, AWhiteSurfaceUnderAWhiteWorldLosesNothing) {
  for (double sigma : {0.01, 0.5, 1.0})
    for (double mu : {0.0, 0.3, 1.0}) {
      EXPECT_NEAR(reference_oren_nayar_white_sky(sigma, glm::dvec3(1.0), mu).x, 1.0, 1e-7) << sigma << ", " << mu;
      if (mu > 0.0) {
        EXPECT_LT(reference_oren_nayar_white_sky(sigma, glm::dvec3(0.5), mu).x, 1.0) << sigma << ", " << mu;
      }
    }
}

// Version 2 materials, every other one with a diffuse roughness (0 to 1), the rest Lambert's (0) or of
// another model: their lanes share the kernel.
std::pair<Scene, GBuffer> rough_scene(unsigned seed, SpecularModel others) {
  testing::RandomSceneSpec spec;
  spec.materials = 6;
  auto [scene, gbuffer] = testing::random_scene(spec, seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> zero_one(0.0, 1.0);
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    Material& m = scene.materials[i];
    if (i % 3 == 2) {
      m.specular_model = others;
      continue;
    }
    m.specular_model = SpecularModel::principled;
    m.version = 2;
    m.base_color = {zero_one(rng), zero_one(rng), 1.2 * zero_one(rng)};  // above 1: Cycles saturates the albedo
    m.metallic = 0.3 * zero_one(rng);
    m.roughness = 0.1 + 0.9 * zero_one(rng);
    m.ior = 1.0 + zero_one(rng);
    m.diffuse_roughness = i % 3 == 0 ? zero_one(rng) : 0.0;
  }
  return {scene, gbuffer};
}

// Float against double, with G's arc cosine in float: the same bound as version 2's own
// (test_shading_principled_v2.cpp, kPrincipledV2Bound); measured worst 3.9e-4 (1 lane, Phong's lanes
// beside). Fujii's t, the colour of the multiple scattering or a missing layering is off by percents.
constexpr double kOrenNayarBound = 2e-3;

TEST(OrenNayar, MatchesTheReferenceUnderPointAndDirectionalLights) {
  PHONGCL_REQUIRE_DEVICE(shader);
  unsigned seed = 9900;
  for (SpecularModel others : {SpecularModel::phong, SpecularModel::principled})
    for (int lanes : {1, 16}) {
      const auto [scene, gbuffer] = rough_scene(++seed, others);
      ShadeOptions options;
      options.lanes = lanes;
      const ShadeResult result = shader.shade(scene, gbuffer, options);
      EXPECT_EQ(result.recipe.value("OREN_NAYAR"), "1");
      const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
      EXPECT_EQ(stats.nonfinite_mismatches, 0u);
      EXPECT_LE(stats.max_rel, kOrenNayarBound) << lanes << " lanes: " << describe_worst(stats);
    }
}

// Area lights and the environment reach the diffuse as Lambert's light: Oren-Nayar's response over
// Lambert's toward the light's centre, and under a white world for the environment (docs/shading.md). A
// diffuse-only material (IOR 1, metallic 0: no specular lobe) under both, against the reference's
// irradiance by quadrature times the same ratios computed from its integrated albedos. Measured worst
// 4.9e-4 (disks; rects 2.2e-4; the reference's uniform world alone is 3.3e-5 off).
TEST(OrenNayar, AreaLightsAndAUniformWorldMatchTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (bool rect : {true, false}) {
    testing::AreaScene s = testing::area_scene(testing::emitters(rect), glm::dvec3(0.0), 1.0, rect ? 9911 : 9912);
    Material& m = s.scene.materials[0];
    m.specular_model = SpecularModel::principled;
    m.version = 2;
    m.base_color = {0.9, 0.5, 0.2};
    m.metallic = 0.0;
    m.ior = 1.0;
    m.diffuse_roughness = 0.8;
    s.scene.environment = EnvironmentLight{};
    s.scene.environment->color = {0.2, 0.3, 0.4};
    s.scene.environment->shadows = false;
    const ShadeResult result = shader.shade(s.scene, s.gbuffer, ShadeOptions{});
    const ErrorStats stats = shading_error(result.image, reference_image(s.scene, s.gbuffer), testing::shaded_mask(s.gbuffer));
    EXPECT_EQ(stats.nonfinite_mismatches, 0u);
    EXPECT_LE(stats.max_rel, 1e-3) << (rect ? "rects" : "disks") << ": " << describe_worst(stats);
  }
}

// Compiled in only where a version 2 material's diffuse roughness reaches Cycles' 1e-5: Lambert's
// version 2, and a roughness below the threshold, leave it out.
TEST(OrenNayar, CompiledInOnlyWhereAMaterialHasADiffuseRoughness) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (double roughness : {0.0, 5e-6, 1e-5}) {
    auto [scene, gbuffer] = rough_scene(9920, SpecularModel::phong);
    for (Material& m : scene.materials) m.diffuse_roughness = m.specular_model == SpecularModel::principled ? roughness : 0.0;
    const ShadeResult result = shader.shade(scene, gbuffer, ShadeOptions{});
    EXPECT_EQ(result.recipe.value("OREN_NAYAR"), roughness >= 1e-5 ? "1" : "0") << roughness;
  }
}

}  // namespace
}  // namespace phongcl
