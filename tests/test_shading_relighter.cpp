// phongcl::Relighter: a resident G-buffer re-shaded after light, material and eye changes must give
// the image the double reference gives for the changed scene, upload only what changed, and rebuild
// the kernel only when the recipe changes; tiles, terms, culling and the report are what
// `phongcl shade` prints and writes.
#include <gtest/gtest.h>

#include <phongcl/phongcl.hpp>

#include "opencl_required.h"
#include "shading_support.h"
#include "shaped_lights.h"

namespace phongcl {
namespace {

using testing::describe_worst;
using testing::kRelativeBound;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;

void expect_matches_reference(const Image& image, const Scene& scene, const GBuffer& gbuffer, const char* step) {
  testing::expect_background_exact(image, scene, gbuffer);
  const ErrorStats stats = shading_error(image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
  EXPECT_EQ(stats.nonfinite_mismatches, 0u) << step;
  EXPECT_LE(stats.max_rel, kRelativeBound) << step << ": " << describe_worst(stats);
}

// In a TEST body: SKIP (FAIL under CI) on a machine without an OpenCL device.
#define PHONGCL_REQUIRE_ANY_DEVICE() PHONGCL_REQUIRE_OPENCL(!available_devices().empty())

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

// Area lights are updates like the others: moved, recoloured, added or removed, the frame is the
// one a new Relighter gives for the changed scene, without packing the G-buffer again.
TEST(Relighter, AreaLightChangesGiveTheImageOfANewRelighter) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  auto made = random_scene({}, 1204);  // not a structured binding: clang 14 cannot capture one
  Scene& scene = made.first;
  const GBuffer& gbuffer = made.second;
  AreaLight rect;
  rect.position = {0.5, 2.0, 1.0};
  rect.direction = {0.0, -1.0, -0.3};
  rect.size = {1.5, 0.8};
  scene.area_lights = {rect};
  Relighter relighter(scene, gbuffer);
  relighter.shade();
  auto expect_as_new = [&](const char* step) {
    const Image image = relighter.shade();
    EXPECT_FALSE(relighter.last_timings().gbuffer_uploaded) << step;
    EXPECT_EQ(image.rgba, Relighter(scene, gbuffer).shade().rgba) << step;  // the same kernel on the same inputs
  };
  scene.area_lights[0].position = {-0.5, 2.5, 0.5};
  scene.area_lights[0].color = {2.0, 1.5, 1.0};
  relighter.set_area_lights(scene.area_lights);
  expect_as_new("moved and recoloured");
  EXPECT_FALSE(relighter.last_timings().rebuilt);
  AreaLight disk = rect;
  disk.shape = AreaShape::disk;
  disk.position = {1.0, 1.0, 2.0};
  scene.area_lights.push_back(disk);
  relighter.set_area_lights(scene.area_lights);
  expect_as_new("a disk added");
  scene.area_lights.clear();
  relighter.set_area_lights(scene.area_lights);
  expect_as_new("none left");
  EXPECT_EQ(relighter.scene().area_lights.size(), 0u);
  disk.size = {-1.0, -1.0};
  EXPECT_THROW(relighter.set_area_lights({disk}), std::invalid_argument);
  expect_as_new("after a refused change");
}

TEST(Relighter, TilesBeyondOneLaunchGiveTheWholeFrame) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  auto [scene, gbuffer] = random_scene({}, 1205);
  const Image whole = Relighter(scene, gbuffer).shade();
  RelighterOptions options;
  options.max_tile_pixels = 200;  // 851 pixels: 5 launches, the last one partial
  Relighter tiled(scene, gbuffer, options);
  const Image pieces = tiled.shade();
  EXPECT_EQ(tiled.last_report().tiles, 5u);
  EXPECT_EQ(pieces.rgba, whole.rgba);  // the same kernel on the same pixels: bit for bit
  // Tiles overwrite each other's packed G-buffer: every frame packs again.
  scene.lights[0].color = {0.5, 2, 1};
  tiled.set_lights(scene.lights);
  expect_matches_reference(tiled.shade(), scene, gbuffer, "tiled, moved light");
  EXPECT_TRUE(tiled.last_timings().gbuffer_uploaded);
}

TEST(Relighter, TermsSumToTheImage) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  const auto [scene, gbuffer] = random_scene({}, 1206);
  TermImages terms;
  EXPECT_THROW(Relighter(scene, gbuffer).shade(terms), std::logic_error);
  RelighterOptions options;
  options.terms = true;
  Relighter relighter(scene, gbuffer, options);
  const Image image = relighter.shade(terms);
  expect_matches_reference(image, scene, gbuffer, "with terms");
  testing::expect_terms_sum_to_image(terms, image, testing::shaded_mask(gbuffer));
}

// The groups come back with the terms, named; a light that changes group is a new recipe (the count
// is compiled in), and a group whose lights all go leaves the layers.
TEST(Relighter, LightGroupsComeBackWithTheTerms) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  auto [scene, gbuffer] = random_scene({}, 1208);
  scene.lights[0].group = "key";
  scene.lights[1].group = "rim";
  RelighterOptions options;
  options.terms = true;
  Relighter relighter(scene, gbuffer, options);
  TermImages terms;
  const Image image = relighter.shade(terms);
  expect_matches_reference(image, scene, gbuffer, "grouped");
  EXPECT_EQ(terms.group_names, (std::vector<std::string>{"key", "rim"}));
  ASSERT_EQ(terms.groups.size(), 2u);
  EXPECT_NE(relighter.kernel_summary().find("2 light groups"), std::string::npos) << relighter.kernel_summary();
  // The key light alone: its diffuse + specular is the key group's layer.
  Scene key = scene;
  key.lights.resize(1);
  TermImages alone;
  Relighter key_only(key, gbuffer, options);
  key_only.shade(alone);
  Image key_light = alone.diffuse;
  for (std::size_t i = 0; i < key_light.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) key_light.pixel(i)[c] += alone.specular.pixel(i)[c];
  const ErrorStats same = testing::shading_error(terms.groups[0], key_light, testing::shaded_mask(gbuffer));
  EXPECT_LE(same.max_rel, 1e-5) << testing::describe_worst(same);
  scene.lights[1].group = "";
  relighter.set_lights(scene.lights);
  relighter.shade(terms);
  EXPECT_EQ(terms.group_names, (std::vector<std::string>{"key"}));
  EXPECT_EQ(terms.groups.size(), 1u);
}

TEST(Relighter, ReportCountsPixelsAndSaysWhatWasCompiled) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  auto [scene, gbuffer] = random_scene({}, 1207);
  gbuffer.normal[1][5] = std::nanf("");
  Relighter relighter(scene, gbuffer);
  relighter.shade();
  const ShadeReport report = relighter.last_report();
  PixelCounts expected;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) expected.add(classify_pixel(gbuffer, i));
  EXPECT_EQ(report.counts.shaded, expected.shaded);
  EXPECT_EQ(report.counts.background, expected.background);
  EXPECT_EQ(report.counts.nonfinite_normal, 1u);
  EXPECT_EQ(report.tiles, 1u);
  EXPECT_EQ(report.point_lights, 3);
  EXPECT_EQ(report.directional_lights, 2);
  EXPECT_EQ(report.kernel_summary, relighter.kernel_summary());
  EXPECT_EQ(report.build_options, relighter.build_options());
  EXPECT_FALSE(report.recipe_reasons.empty());
  EXPECT_FALSE(report.culled);
  // A re-shade finds the same pixels without packing them again.
  relighter.shade();
  EXPECT_FALSE(relighter.last_timings().gbuffer_uploaded);
  EXPECT_EQ(relighter.last_report().counts.nonfinite_normal, 1u);
}

TEST(Relighter, ManyLightsWithARangeAreCulledPerTile) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  auto [scene, gbuffer] = random_scene({64, 48, 0, 1, 4}, 1208);
  testing::add_shaped_lights(scene, {kAutoCullingLights}, 1208);
  Relighter relighter(scene, gbuffer);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "culled");
  const ShadeReport report = relighter.last_report();
  ASSERT_TRUE(report.culled) << report.kernel_summary;
  EXPECT_GT(report.culling.shaded_tiles, 0u);
  EXPECT_LE(report.culling.max_lights_per_tile, static_cast<std::size_t>(kAutoCullingLights));
  // New lights are culled again over the resident G-buffer.
  scene.lights.resize(scene.lights.size() - 1);
  testing::add_shaped_lights(scene, {1}, 1209);
  relighter.set_lights(scene.lights);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "culled, new light");
  EXPECT_FALSE(relighter.last_timings().gbuffer_uploaded);
  // The tiles' boxes are kept with the packed G-buffer, and taken again with it: after a new eye
  // (far enough that the old, eye-relative boxes would meet no light), and for another frame of the
  // same size.
  scene.camera.eye = {40.0, -30.0, 300.0};
  relighter.set_camera_eye(scene.camera.eye);
  expect_matches_reference(relighter.shade(), scene, gbuffer, "culled, new eye");
  EXPECT_TRUE(relighter.last_timings().gbuffer_uploaded);
  auto [next_scene, next_gbuffer] = random_scene({64, 48, 0, 1, 4}, 1213);
  testing::add_shaped_lights(next_scene, {kAutoCullingLights}, 1213);
  relighter.set_frame(next_scene, GBuffer(next_gbuffer));
  expect_matches_reference(relighter.shade(), next_scene, next_gbuffer, "culled, next frame");
  EXPECT_TRUE(relighter.last_report().culled);
  // A frame shaded without culling packs the planes too: the culling after it takes its boxes again.
  auto [third_scene, third_gbuffer] = random_scene({64, 48, 0, 1, 4}, 1214);
  third_scene.camera.eye = {-40.0, 30.0, -300.0};
  testing::add_shaped_lights(third_scene, {kAutoCullingLights}, 1214);
  Scene one_light_short = third_scene;
  one_light_short.lights.pop_back();
  relighter.set_frame(one_light_short, GBuffer(third_gbuffer));
  relighter.shade();
  EXPECT_FALSE(relighter.last_report().culled);
  relighter.set_lights(third_scene.lights);
  expect_matches_reference(relighter.shade(), third_scene, third_gbuffer, "culled after a frame without");
  EXPECT_TRUE(relighter.last_report().culled);
  EXPECT_FALSE(relighter.last_timings().gbuffer_uploaded);
}

TEST(Relighter, OneRelighterShadesASequenceOfFrames) {
  PHONGCL_REQUIRE_ANY_DEVICE();
  Relighter relighter{RelighterOptions{}};
  EXPECT_EQ(relighter.width(), 0);
  EXPECT_THROW(relighter.shade(), std::logic_error);
  for (unsigned seed : {1210u, 1211u}) {
    RandomSceneSpec spec;
    spec.width += static_cast<int>(seed % 2);  // frames of other sizes too
    auto [scene, gbuffer] = random_scene(spec, seed);
    relighter.set_frame(scene, GBuffer(gbuffer));
    EXPECT_EQ(relighter.width(), gbuffer.width);
    expect_matches_reference(relighter.shade(), scene, gbuffer, "sequence frame");
    EXPECT_TRUE(relighter.last_timings().gbuffer_uploaded);
  }
  // A frame the scene cannot shade is refused and the previous one kept.
  auto [scene, gbuffer] = random_scene({}, 1212);
  scene.materials.resize(1);
  EXPECT_THROW(relighter.set_frame(scene, GBuffer(gbuffer)), InputError);
  EXPECT_EQ(relighter.width(), RandomSceneSpec{}.width + 1);
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
