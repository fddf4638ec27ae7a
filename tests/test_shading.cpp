// The OpenCL kernel against the independent double-precision reference, on random and bundled
// scenes, every precision variant, specialised and general, tiled and whole.
#include <unistd.h>

#include <filesystem>
#include <limits>

#include "common/error.h"

#include "shading_support.h"
#include "temp_dir.h"
#include "renderer_files.h"

namespace phongcl {
namespace {

using testing::default_scene;
using testing::describe_worst;
using testing::in_camera_space;
using testing::kRelativeBound;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;

ErrorStats error_against_reference(PhongShader& shader, const Scene& scene, const GBuffer& gbuffer,
                                   const ShadeOptions& options, Image* kernel_image = nullptr) {
  const ShadeResult result = shader.shade(scene, gbuffer, options);
  const Image reference = reference_image(scene, gbuffer);
  if (kernel_image) *kernel_image = result.image;
  testing::expect_background_exact(result.image, scene, gbuffer);
  return shading_error(result.image, reference, testing::shaded_mask(gbuffer));
}

TEST(Shading, RandomGBuffersMatchReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (unsigned seed = 6502; seed < 6512; ++seed) {
    RandomSceneSpec spec;
    spec.point_lights = static_cast<int>(seed % 5) * 4;        // 0, 4, 8, 12, 16
    spec.directional_lights = static_cast<int>(seed * 7 % 17);  // 0 to 16
    spec.per_pixel_materials = seed % 2 == 0;
    const auto [scene, gbuffer] = random_scene(spec, seed);
    const ErrorStats stats = error_against_reference(shader, scene, gbuffer, {});
    EXPECT_EQ(stats.nonfinite_mismatches, 0u) << "seed " << seed;
    EXPECT_LE(stats.max_rel, kRelativeBound) << "seed " << seed << ": " << describe_worst(stats);
  }
}

// Every OpenCL vector width the kernel can be built for, not only this device's preferred one (a
// GPU gets 1): material tables picked with selects (<= lanes entries) and gathered (more), per-pixel
// materials, both light types, a point light at a shaded point (the rescaling branch), a partial
// last vector (37 x 23 pixels), in precise, fast and double.
TEST(Shading, EveryLaneCountMatchesReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (int lanes : {1, 2, 4, 8, 16}) {
    for (int materials : {1, 3, lanes, 20}) {
      for (bool per_pixel : {false, true}) {
        RandomSceneSpec spec;
        spec.materials = materials;
        spec.per_pixel_materials = per_pixel;
        auto [scene, gbuffer] = random_scene(spec, 100 * lanes + materials + per_pixel);
        const glm::dvec3 first_pixel(gbuffer.position[0][0], gbuffer.position[1][0], gbuffer.position[2][0]);
        scene.lights.push_back({LightType::point, first_pixel, {}, glm::dvec3(0.5)});
        ShadeOptions options;
        options.lanes = lanes;
        const bool selects = !per_pixel && materials > 1 && materials <= lanes;
        EXPECT_EQ(make_recipe(scene, gbuffer, shader.compute().device.info, options).value("MATERIAL_COUNT") ==
                      std::to_string(materials),
                  selects)
            << lanes << " lanes, " << materials << " materials";
        const ErrorStats stats = error_against_reference(shader, scene, gbuffer, options);
        EXPECT_LE(stats.max_rel, kRelativeBound) << lanes << " lanes, " << materials << " materials"
                                                 << (per_pixel ? " per pixel" : "") << ": " << describe_worst(stats);
      }
    }
    const auto [scene, gbuffer] = random_scene({}, 7 * lanes);
    ShadeOptions options;
    options.lanes = lanes;
    options.precision = Precision::fast;
    const ErrorStats fast = error_against_reference(shader, scene, gbuffer, options);
    EXPECT_LE(fast.max_rel, kRelativeBound) << lanes << " lanes, fast: " << describe_worst(fast);
    options.precision = Precision::double_precision;
    const ErrorStats stats = error_against_reference(shader, scene, gbuffer, options);
    // Light positions reach the kernel as floats (rebased to the eye first), and q up to 1000
    // amplifies their rounding in the highlights: 1e-4, not the double reference's 1e-15.
    EXPECT_LE(stats.max_rel, 1e-4) << lanes << " lanes, double: " << describe_worst(stats);
  }
  ShadeOptions three_lanes;
  three_lanes.lanes = 3;
  const auto [scene, gbuffer] = random_scene({}, 1);
  EXPECT_THROW(shader.shade(scene, gbuffer, three_lanes), std::invalid_argument);
}

TEST(Shading, BundledScenesMatchReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes")) {
    const auto file = entry.path() / "scene.json";
    if (!std::filesystem::exists(file)) continue;
    ++scenes;
    const Scene scene = load_scene(file);
    const GBuffer gbuffer = generate_gbuffer(scene);
    const ErrorStats stats = error_against_reference(shader, scene, gbuffer, {});
    EXPECT_LE(stats.max_rel, kRelativeBound) << file << ": " << describe_worst(stats);
    EXPECT_EQ(stats.nonfinite_mismatches, 0u) << file;
  }
  EXPECT_GE(scenes, 3);
}

TEST(Shading, DoublePrecisionVariantMatchesReferenceClosely) {
  PHONGCL_REQUIRE_DEVICE(shader);
  if (!shader.compute().device.info.has_fp64) GTEST_SKIP() << "device has no fp64";
  const auto [scene, gbuffer] = random_scene({}, 7);
  const ErrorStats stats = error_against_reference(shader, scene, gbuffer, {Precision::double_precision});
  // Inputs are the same floats, arithmetic in double: only the final rounding to float remains.
  EXPECT_LE(stats.max_rel, 1e-6) << describe_worst(stats);
}

TEST(Shading, FastAndHalfStorageVariantsStayWithinTheirMeasuredBounds) {
  PHONGCL_REQUIRE_DEVICE(shader);
  RandomSceneSpec spec;
  spec.max_shininess = 100.0;
  const auto [scene, gbuffer] = random_scene(spec, 11);
  // fast: precise's formulas under -cl-fast-relaxed-math, which may reassociate and contract them
  // and drop the compensated light sum: precise's bound. half storage: inputs rounded to 11 bits
  // (relative 2^-11 = 4.9e-4) before the same float math; the diffuse term inherits that, the
  // specular term q times more at q = 100.
  const ErrorStats fast = error_against_reference(shader, scene, gbuffer, {Precision::fast});
  EXPECT_LE(fast.max_rel, kRelativeBound) << "fast: " << describe_worst(fast);
  const ErrorStats half = error_against_reference(shader, scene, gbuffer, {Precision::half_storage});
  EXPECT_LE(half.max_rel, 0.5) << "half-storage: " << describe_worst(half);
  EXPECT_EQ(fast.nonfinite_mismatches + half.nonfinite_mismatches, 0u);
}

// Scenes that exercise each specialisation: every light type alone, many lights (run-time
// counts), one material, per-pixel materials, no specular, no ambient.
std::vector<std::pair<std::string, std::pair<Scene, GBuffer>>> specialisation_scenes() {
  std::vector<std::pair<std::string, std::pair<Scene, GBuffer>>> scenes;
  auto add = [&](const std::string& name, RandomSceneSpec spec, auto&& edit) {
    auto scene_and_gbuffer = random_scene(spec, 21 + static_cast<unsigned>(scenes.size()));
    edit(scene_and_gbuffer.first);
    scenes.emplace_back(name, std::move(scene_and_gbuffer));
  };
  auto unchanged = [](Scene&) {};
  RandomSceneSpec spec;
  add("mixed lights, material table", spec, unchanged);
  spec.directional_lights = 0;
  add("point lights only", spec, unchanged);
  spec.point_lights = 0;
  spec.directional_lights = 3;
  add("directional lights only", spec, unchanged);
  spec.point_lights = spec.directional_lights = 20;
  add("more lights than unroll (run-time counts)", spec, unchanged);
  spec = {};
  spec.materials = 1;
  add("single material", spec, unchanged);
  spec.per_pixel_materials = true;
  add("per-pixel materials", spec, unchanged);
  spec = {};
  add("no specular", spec, [](Scene& s) { for (Material& m : s.materials) m.ks = glm::dvec3(0.0); });
  add("no ambient", spec, [](Scene& s) { s.ambient = glm::dvec3(0.0); });
  return scenes;
}

TEST(Shading, GeneralKernelGivesTheSameImageAsSpecialised) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (const auto& [name, scene_and_gbuffer] : specialisation_scenes()) {
    const auto& [scene, gbuffer] = scene_and_gbuffer;
    const ShadeResult specialised = shader.shade(scene, gbuffer, {});
    const ShadeResult general = shader.shade(scene, gbuffer, {Precision::precise, false});
    EXPECT_NE(specialised.build_options, general.build_options) << name;
    // Same formula and precision; only the compiler's scheduling of unrolled loops differs, and
    // terms compiled out are exactly zero in the general kernel: a few ulp at most.
    const ErrorStats stats = shading_error(specialised.image, general.image);
    EXPECT_LE(stats.max_rel, 1e-5) << name << ": " << describe_worst(stats);
    const ErrorStats against_reference =
        shading_error(specialised.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
    EXPECT_LE(against_reference.max_rel, kRelativeBound) << name << ": " << describe_worst(against_reference);
  }
}

TEST(Shading, DirectionalOnlyDiffuseSceneCompilesOutPointLightsAndSpecular) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const Scene scene = load_scene(std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes/directional_diffuse/scene.json");
  const GBuffer gbuffer = generate_gbuffer(scene);
  const ShadeResult result = shader.shade(scene, gbuffer, {});
  EXPECT_EQ(result.recipe.value("SPECULAR"), "0") << result.build_options;
  EXPECT_EQ(result.recipe.value("POINT_LIGHTS"), "0") << result.build_options;
  EXPECT_EQ(result.recipe.value("DIRECTIONAL_LIGHTS"), "1") << result.build_options;
  const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer));
  EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
}

TEST(Shading, TilesGiveTheSameImageAsOneLaunch) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto [scene, gbuffer] = random_scene({}, 33);
  const ShadeResult whole = shader.shade(scene, gbuffer, {});
  ShadeOptions tiled;
  tiled.max_tile_pixels = 97;  // does not divide 37 x 23 = 851: the last tile is partial
  const ShadeResult pieces = shader.shade(scene, gbuffer, tiled);
  // Tiles are rounded up to whole work-items of the kernel's lanes.
  const std::size_t lanes = static_cast<std::size_t>(pieces.recipe.lanes);
  const std::size_t stride = (tiled.max_tile_pixels + lanes - 1) / lanes * lanes;
  EXPECT_EQ(pieces.tiles, (gbuffer.pixel_count() + stride - 1) / stride);
  EXPECT_GT(pieces.tiles, 5u);
  EXPECT_EQ(whole.tiles, 1u);
  ASSERT_EQ(whole.image.rgba.size(), pieces.image.rgba.size());
  for (std::size_t i = 0; i < whole.image.rgba.size(); ++i) {
    ASSERT_EQ(whole.image.rgba[i], pieces.image.rgba[i]) << "value " << i << ": same kernel, same inputs";
  }
}

TEST(Shading, CountsNonFiniteAndBackgroundPixels) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = random_scene({}, 44);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  gbuffer.material[0] = 0.0f;
  gbuffer.position[1][0] = nan;
  gbuffer.material[1] = 0.0f;
  gbuffer.normal[2][1] = std::numeric_limits<float>::infinity();
  const ShadeResult result = shader.shade(scene, gbuffer, {});
  EXPECT_EQ(result.counts.nonfinite_position, 1u);
  EXPECT_EQ(result.counts.nonfinite_normal, 1u);
  EXPECT_EQ(result.counts.shaded + result.counts.background + 2, gbuffer.pixel_count());
  testing::expect_background_exact(result.image, scene, gbuffer);
}

TEST(Shading, MaterialIndexOutOfRangeIsAnInputError) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = random_scene({}, 55);
  gbuffer.material[5] = 99.0f;
  EXPECT_THROW(shader.shade(scene, gbuffer, {}), InputError);
}

TEST(Shading, HalfStorageRefusesValuesBeyondHalfRange) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = random_scene({}, 66);
  gbuffer.material[3] = 0.0f;
  gbuffer.position[0][3] = 1e5f;  // 1e5 from the eye: beyond half's 65504
  try {
    shader.shade(scene, gbuffer, {Precision::half_storage});
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("half"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("P.X"), std::string::npos) << error.what();
  }
}

TEST(ProgramCache, SecondBuildHitsMemoryThenDisk) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const testing::TempDir dir;
  const auto [scene, gbuffer] = random_scene({}, 77);
  {
    ProgramCache cache(dir.path);
    PhongShader fresh(shader.compute(), cache);
    EXPECT_EQ(fresh.shade(scene, gbuffer, {}).cache, CacheOutcome::compiled);
    EXPECT_EQ(fresh.shade(scene, gbuffer, {}).cache, CacheOutcome::memory_hit);
  }
  ProgramCache next_process(dir.path);
  PhongShader again(shader.compute(), next_process);
  const ShadeResult result = again.shade(scene, gbuffer, {});
  EXPECT_EQ(result.cache, CacheOutcome::disk_hit);
  const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer));
  EXPECT_LE(stats.max_rel, kRelativeBound) << "program loaded from the disk cache: " << describe_worst(stats);
}

TEST(Shading, TermImagesSumToTheCombinedImage) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto [scene, gbuffer] = random_scene({}, 88);
  ShadeOptions options;
  options.write_terms = true;
  const ShadeResult result = shader.shade(scene, gbuffer, options);
  testing::expect_terms_sum_to_image(result.terms, result.image, testing::shaded_mask(gbuffer));
  const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
  EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
}

TEST(CameraSpace, ShadesLikeWorldSpace) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, g] = default_scene();
  AreaLight rect;  // its position, direction and up turn with the camera too
  rect.position = scene.camera.look_at + glm::dvec3(0.5, 3.0, 0.5);
  rect.direction = {0.1, -1.0, 0.2};
  rect.up = {0.0, 0.0, 1.0};
  rect.size = {1.5, 0.7};
  rect.color = glm::dvec3(0.8);
  scene.area_lights.push_back(rect);
  const Image world = shader.shade(scene, g, {}).image;
  for (const auto& [what, camera_gbuffer] :
       {std::pair{"moved by world_to_camera", in_camera_space(g, scene.camera)},
        std::pair{"generated from the camera-space scene", generate_gbuffer(to_camera_space(scene))}}) {
    SCOPED_TRACE(what);
    const Image camera = shader.shade(to_camera_space(scene), camera_gbuffer, {}).image;
    // Same bound as the kernel-vs-reference suites: the inputs differ only by float rounding of a
    // rigid motion (a few ulps of P and N), far below it.
    const ErrorStats stats = shading_error(camera, world, testing::shaded_mask(g));
    EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
    EXPECT_EQ(stats.nonfinite_mismatches, 0u);
  }
}

}  // namespace
}  // namespace phongcl
