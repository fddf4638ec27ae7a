// phongcl::Relighter: a resident G-buffer re-shaded after light, material and eye changes must give
// the image the double reference gives for the changed scene, upload only what changed, and rebuild
// the kernel only when the recipe changes.
#include <gtest/gtest.h>

#include <phongcl/phongcl.hpp>

#include "shading_support.h"

namespace phongcl {
namespace {

using testing::describe_worst;
using testing::random_scene;
using testing::RandomSceneSpec;

// The product's bound, as in test_shading.cpp (where it is derived).
constexpr double kRelativeBound = 5e-4;
constexpr double kAbsoluteFloor = 1e-6;

void expect_matches_reference(const Image& image, const Scene& scene, const GBuffer& gbuffer, const char* step) {
  testing::expect_background_exact(image, scene, gbuffer);
  const ErrorStats stats =
      compare_images(image, reference_image(scene, gbuffer), kAbsoluteFloor, testing::shaded_mask(gbuffer));
  EXPECT_EQ(stats.nonfinite_mismatches, 0u) << step;
  EXPECT_LE(stats.max_rel, kRelativeBound) << step << ": " << describe_worst(stats);
}

// In a TEST body: SKIP on a machine without an OpenCL device.
#define PHONGCL_REQUIRE_ANY_DEVICE() \
  if (available_devices().empty()) GTEST_SKIP() << "no OpenCL device on this machine"

TEST(Relighter, EveryChangeMatchesTheReferenceForTheChangedScene) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  auto [scene, gbuffer] = random_scene({}, 1201);
  Relighter relighter(scene, gbuffer);
  EXPECT_EQ(relighter.width(), gbuffer.width);
  EXPECT_EQ(relighter.height(), gbuffer.height);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "first frame");
  EXPECT_TRUE(relighter.last_timings().gbuffer_uploaded);

  // Same count and types: new values, the same kernel, no G-buffer upload.
  scene.lights[0].color = {2, 2, 2};
  scene.lights[1].position = {-4, 3, 2};
  relighter.set_lights(scene.lights);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "moved light");
  EXPECT_FALSE(relighter.last_timings().rebuilt);
  EXPECT_FALSE(relighter.last_timings().gbuffer_uploaded);

  scene.materials[2].kd = {0.1, 0.9, 0.2};
  scene.materials[3].shininess = 7;
  relighter.set_materials(scene.materials);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "new materials");
  EXPECT_FALSE(relighter.last_timings().rebuilt);

  // Positions are stored relative to the eye: a new eye re-packs the G-buffer.
  scene.camera.eye = {2.0, -1.0, 7.0};
  relighter.set_camera_eye(scene.camera.eye);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "new eye");
  EXPECT_TRUE(relighter.last_timings().gbuffer_uploaded);

  // The light count is compiled in: one more light is a new recipe.
  scene.lights.push_back({LightType::directional, {}, {0, -1, 0}, {0.3, 0.3, 0.3}});
  relighter.set_lights(scene.lights);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "one more light");
  EXPECT_TRUE(relighter.last_timings().rebuilt);
  EXPECT_EQ(relighter.scene().lights.size(), scene.lights.size());
}

TEST(Relighter, ShadeIntoACallersBufferGivesTheSameImage) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  const auto [scene, gbuffer] = random_scene({}, 1202);
  Relighter relighter(scene, gbuffer);
  const Image image = relighter.shade();
  std::vector<float> buffer(image.rgba.size(), -1.0f);
  relighter.shade_into(buffer.data(), buffer.size());
  EXPECT_EQ(buffer, image.rgba);  // the same kernel on the same inputs: bit for bit
  EXPECT_THROW(relighter.shade_into(buffer.data(), buffer.size() - 4), std::invalid_argument);
}

TEST(Relighter, BadChangesAreRefusedAndTheStateKept) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  const auto [scene, gbuffer] = random_scene({}, 1203);
  Relighter relighter(scene, gbuffer);
  std::vector<Light> lights = scene.lights;
  lights[0].color = {-1, 0, 0};
  EXPECT_THROW(relighter.set_lights(lights), std::invalid_argument);
  lights[0].color = {1, 1, 1};
  lights[0].position.x = std::nan("");
  EXPECT_THROW(relighter.set_lights(lights), std::invalid_argument);
  // The G-buffer uses indices 0 to 3: a table of 2 cannot shade it.
  const std::vector<Material> two(scene.materials.begin(), scene.materials.begin() + 2);
  EXPECT_THROW(relighter.set_materials(two), InputError);
  EXPECT_THROW(relighter.set_camera_eye({0, INFINITY, 0}), std::invalid_argument);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "after refused changes");
}

TEST(Relighter, UnknownDeviceIsAClearError) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  const auto [scene, gbuffer] = random_scene({}, 1204);
  RelighterOptions options;
  options.device = "no-such-device-anywhere";
  EXPECT_THROW(Relighter(scene, gbuffer, options), std::runtime_error);
}

}  // namespace
}  // namespace phongcl
