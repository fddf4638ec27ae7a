// Falloff, range windows, spot cones (with cosine powers) and light linking: the kernel against the
// double reference in every precision variant but half-storage, each specialised combination against
// the general kernel, and what reaches the kernel's build options; light groups' layers.
#include <functional>
#include <numbers>
#include <sstream>

#include "peers/many_lights.h"
#include "shading_support.h"
#include "shaped_lights.h"

namespace phongcl {
namespace {

using testing::add_shaped_lights;
using testing::describe_worst;
using testing::kRelativeBound;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;
using testing::ShapedLightSpec;

// The product's bound (shading_support.h says why float meets it) holds for the light shapes too.
// The new factors add a few ulp: 1/d^k (k roundings of a correctly rounded rsqrt), the window
// (1 - x^4 loses digits only where the window, and so the light's share, is near 0) and the
// smoothstep (s's error is about 3e-7 over a penumbra of at least 5 degrees, cos difference >=
// 0.01: 3e-5 of s, but only where cone ~ s^2 is small beside the pixel's other terms).

struct Case {
  const char* name;
  ShapedLightSpec lights;
};

std::vector<Case> feature_cases() {
  std::vector<Case> cases;
  auto add = [&](const char* name, auto edit) {
    ShapedLightSpec spec;
    spec.falloff = spec.range = spec.spots = false;
    edit(spec);
    cases.push_back({name, spec});
  };
  add("quadratic falloff", [](ShapedLightSpec& s) { s.falloff = true; });
  add("mixed falloff", [](ShapedLightSpec& s) { s.falloff = s.mixed_falloff = true; });
  add("range", [](ShapedLightSpec& s) { s.range = true; });
  add("soft spots", [](ShapedLightSpec& s) { s.spots = true; });
  add("hard spots", [](ShapedLightSpec& s) { s.spots = s.hard_spots = true; });
  add("linking", [](ShapedLightSpec& s) { s.linking = true; });
  add("everything", [](ShapedLightSpec& s) { s.falloff = s.mixed_falloff = s.range = s.spots = s.linking = true; });
  add("quadratic, range, spots", [](ShapedLightSpec& s) { s.falloff = s.range = s.spots = true; });
  add("spots with cosine powers", [](ShapedLightSpec& s) {
    s.spots = true;
    s.max_cosine_power = 40.0;
  });
  return cases;
}

std::pair<Scene, GBuffer> shaped_scene(const Case& c, unsigned seed, int materials = 4) {
  RandomSceneSpec spec;
  spec.point_lights = 1;  // one plain point light beside the shaped ones
  spec.directional_lights = 1;
  spec.materials = materials;
  auto [scene, gbuffer] = random_scene(spec, seed);
  add_shaped_lights(scene, c.lights, seed + 1);
  return {scene, gbuffer};
}

ErrorStats kernel_vs_reference(PhongShader& shader, const Scene& scene, const GBuffer& gbuffer,
                               const ShadeOptions& options) {
  const ShadeResult result = shader.shade(scene, gbuffer, options);
  testing::expect_background_exact(result.image, scene, gbuffer);
  const std::vector<bool> mask = testing::away_from_hard_edges(scene, gbuffer, testing::shaded_mask(gbuffer));
  return shading_error(result.image, reference_image(scene, gbuffer), mask);
}

TEST(Lights, EveryFeatureMatchesReferenceInEveryVariantAndLaneCount) {
  PHONGCL_REQUIRE_DEVICE(shader);
  unsigned seed = 9100;
  for (const Case& c : feature_cases()) {
    for (Precision precision : {Precision::precise, Precision::fast, Precision::double_precision}) {
      if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
      for (int lanes : {1, 16}) {
        const auto [scene, gbuffer] = shaped_scene(c, ++seed);
        ShadeOptions options;
        options.precision = precision;
        options.lanes = lanes;
        const ErrorStats stats = kernel_vs_reference(shader, scene, gbuffer, options);
        EXPECT_EQ(stats.nonfinite_mismatches, 0u) << c.name;
        EXPECT_LE(stats.max_rel, kRelativeBound) << c.name << ", " << to_string(precision) << ", " << lanes
                                                 << " lanes: " << describe_worst(stats);
      }
    }
  }
}

// More than 32 materials: linking masks of two words.
TEST(Lights, LinkingBeyondThirtyTwoMaterials) {
  PHONGCL_REQUIRE_DEVICE(shader);
  ShapedLightSpec spec;
  spec.linking = true;
  const auto [scene, gbuffer] = shaped_scene({"linking, 40 materials", spec}, 77, 40);
  const ShadeResult result = shader.shade(scene, gbuffer, {});
  EXPECT_EQ(result.recipe.value("LIGHT_LINKING"), "2") << result.build_options;
  const ErrorStats stats = kernel_vs_reference(shader, scene, gbuffer, {});
  EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
}

TEST(Lights, EachSpecialisedCombinationMatchesTheGeneralKernel) {
  PHONGCL_REQUIRE_DEVICE(shader);
  ShadeOptions general;
  general.specialise = false;
  for (int mask = 0; mask < 16; ++mask) {
    ShapedLightSpec spec;
    spec.falloff = mask & 1;
    spec.range = mask & 2;
    spec.spots = mask & 4;
    spec.linking = mask & 8;
    const auto [scene, gbuffer] = shaped_scene({"combination", spec}, 500 + static_cast<unsigned>(mask));
    const ShadeResult specialised = shader.shade(scene, gbuffer, {});
    const Recipe& recipe = specialised.recipe;
    const std::string& options = specialised.build_options;
    EXPECT_EQ(recipe.value("FALLOFF") != "0" || recipe.value("FALLOFF_MIXED") == "1", spec.falloff) << options;
    EXPECT_EQ(recipe.value("RANGE_WINDOW") == "1", spec.range) << options;
    EXPECT_EQ(recipe.value("SPOT_LIGHTS") == "1", spec.spots) << options;
    EXPECT_EQ(recipe.value("LIGHT_LINKING") == "1", spec.linking) << options;
    const ShadeResult unspecialised = shader.shade(scene, gbuffer, general);
    // Both are float, same formula: a few ulp of the light sum apart, far inside the product's bound.
    const ErrorStats stats = shading_error(specialised.image, unspecialised.image,
                                           testing::away_from_hard_edges(scene, gbuffer, testing::shaded_mask(gbuffer)));
    EXPECT_LE(stats.max_rel, 1e-5) << "combination " << mask << ": " << describe_worst(stats);
  }
}

// The cosine power is decided by the scene in the general kernel too: without it, the general kernel
// is the one from before cosine powers; with it, the powered cones still match the reference.
TEST(Lights, TheGeneralKernelCompilesTheCosinePowerOnlyForPoweredSpots) {
  PHONGCL_REQUIRE_DEVICE(shader);
  ShadeOptions general;
  general.specialise = false;
  for (double max_power : {0.0, 40.0}) {
    ShapedLightSpec spec;
    spec.spots = true;
    spec.max_cosine_power = max_power;
    const auto [scene, gbuffer] = shaped_scene({"spots", spec}, 640);
    const ShadeResult result = shader.shade(scene, gbuffer, general);
    EXPECT_EQ(result.recipe.value("SPOT_COSINE_POWER"), max_power > 0.0 ? "1" : "0") << result.build_options;
    const ErrorStats stats = kernel_vs_reference(shader, scene, gbuffer, general);
    EXPECT_LE(stats.max_rel, kRelativeBound) << "max power " << max_power << ": " << describe_worst(stats);
  }
}

// A scene whose lights use no shape (point and directional lights without falloff, range, cone or
// linking) compiles every shape's flag as 0: its kernel is the one without light shapes.
TEST(Lights, UnshapedLightsBuildNoShapeOptions) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto [scene, gbuffer] = random_scene({}, 3);
  const Recipe recipe = make_recipe(scene, gbuffer, shader.compute().device.info, {});
  for (const char* shape : {"FALLOFF", "FALLOFF_MIXED", "RANGE_WINDOW", "SPOT_LIGHTS", "SPOT_COSINE_POWER", "LIGHT_LINKING",
                           "TILED_CULLING"})
    EXPECT_EQ(recipe.value(shape), "0") << shape << ": " << recipe.build_options();
}

// d -> 0 with 1/d^3: +Inf where the exact value exceeds float, never NaN, and a colour channel or
// kd of exactly 0 stays 0 (0 * Inf would be NaN).
TEST(Lights, OverflowingFalloffGivesInfinityNotNaN) {
  PHONGCL_REQUIRE_DEVICE(shader);
  RandomSceneSpec spec;
  spec.point_lights = spec.directional_lights = 0;
  spec.materials = 1;
  spec.background_fraction = 0.0;
  auto [scene, gbuffer] = random_scene(spec, 5);
  scene.materials[0].kd = scene.materials[0].ks = {1.0, 0.0, 1.0};
  scene.materials[0].ka = glm::dvec3(0.0);
  // Positions reach the kernel as floats relative to the eye: d = 1e-20 survives only near it.
  scene.camera.eye = glm::dvec3(0.0);
  const double z = -1e-14;
  for (int c = 0; c < 3; ++c) {
    gbuffer.position[c][0] = c == 2 ? static_cast<float>(z) : 0.0f;
    gbuffer.normal[c][0] = c == 2 ? 1.0f : 0.0f;
  }
  Light light;
  light.position = {0.0, 0.0, z + 1e-20};
  light.color = {1.0, 1.0, 0.0};
  light.falloff = Falloff::cubic;
  scene.lights = {light};
  for (Precision precision : {Precision::precise, Precision::double_precision}) {
    ShadeOptions options;
    options.precision = precision;
    const ShadeResult result = shader.shade(scene, gbuffer, options);
    const float* pixel = result.image.pixel(0);
    EXPECT_EQ(pixel[0], std::numeric_limits<float>::infinity()) << to_string(precision);
    EXPECT_EQ(pixel[1], 0.0f) << to_string(precision) << ": kd.g = ks.g = 0";
    EXPECT_EQ(pixel[2], 0.0f) << to_string(precision) << ": colour.b = 0";
    for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_FALSE(std::isnan(result.image.pixel(i)[c])) << "pixel " << i;
  }
}

// The default scene's geometry at width x height, its lights replaced by `count` ranged ones that
// reach `reach` of them per shaded pixel on average.
std::pair<Scene, GBuffer> default_scene_with_many_lights(int width, int height, int count, double reach) {
  Scene scene = load_scene(std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes/default/scene.json");
  scene.camera.width = width;
  scene.camera.height = height;
  GBuffer gbuffer = generate_gbuffer(scene);
  return {with_many_lights(scene, gbuffer, count, reach), std::move(gbuffer)};
}

// The default scene at 203 x 97 (a width no tile size or lane count divides) with 300 ranged lights:
// tiled culling must give the unculled image to float rounding (a culled light adds exactly 0;
// only the grouping of the compensated sum differs) and match the reference, for lanes 1 and 16,
// tiles of 16, 6 and 5 (their boxes taken in bands of 4, 2 and 1 rows; work-items reaching into the
// next tile), and launches split into pieces. The lists lead with lights that hold all of their tile,
// and the rest, whose ranges the shading tests, are there too.
TEST(Lights, TiledCullingEqualsUnculledAndReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = default_scene_with_many_lights(203, 97, 300, 12.0);
  scene.lights.push_back({LightType::directional, {}, {-0.3, -1.0, -0.5}, glm::dvec3(0.2)});
  const Image reference = reference_image(scene, gbuffer);
  const std::vector<bool> mask = testing::shaded_mask(gbuffer);
  for (int lanes : {1, 16}) {
    ShadeOptions unculled;
    unculled.lanes = lanes;
    unculled.culling = Culling::none;
    const ShadeResult all = shader.shade(scene, gbuffer, unculled);
    EXPECT_EQ(all.recipe.value("TILED_CULLING"), "0");
    for (int tile : {16, 6, 5}) {
      for (std::size_t pieces : {std::size_t{0}, std::size_t{4001}}) {
        ShadeOptions tiled = unculled;
        tiled.culling = Culling::automatic;  // 300 lights with a range: automatic chooses tiles
        tiled.tile_size = tile;
        tiled.max_tile_pixels = pieces;
        const ShadeResult culled = shader.shade(scene, gbuffer, tiled);
        const std::string where = std::to_string(lanes) + " lanes, tile " + std::to_string(tile) +
                                  (pieces ? ", in pieces" : "");
        ASSERT_EQ(culled.recipe.value("TILED_CULLING"), "1") << culled.build_options;
        const ErrorStats same = shading_error(culled.image, all.image, mask);
        EXPECT_LE(same.max_rel, 1e-5) << where << ": " << describe_worst(same);
        EXPECT_EQ(same.nonfinite_mismatches, 0u) << where;
        const ErrorStats exact = shading_error(culled.image, reference, mask);
        EXPECT_LE(exact.max_rel, kRelativeBound) << where << ": " << describe_worst(exact);
        // The culling must have culled: a tile keeps far fewer than all 300 lights.
        EXPECT_GT(culled.culling.shaded_tiles, 0u) << where;
        EXPECT_LT(culled.culling.mean_lights_per_tile(), 150.0) << where;
        EXPECT_LT(culled.culling.kept_pairs, 0.5 * 300.0 * static_cast<double>(culled.counts.shaded)) << where;
        EXPECT_GT(culled.culling.holding_entries, 0.0) << where;
        EXPECT_LT(culled.culling.holding_entries, culled.culling.list_entries) << where;
      }
    }
  }
}

// Spots and linking inside tiles; lights without a range are in every tile's list.
TEST(Lights, TiledCullingKeepsUnrangedLightsEverywhere) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = default_scene_with_many_lights(64, 48, 80, 10.0);
  scene.lights[3].range = 0.0;  // reaches everything
  scene.lights[4].materials = std::vector<int>{1, 3};
  ShadeOptions tiled;
  tiled.culling = Culling::tiled;
  const ShadeResult culled = shader.shade(scene, gbuffer, tiled);
  EXPECT_GE(culled.culling.mean_lights_per_tile(), 1.0);
  EXPECT_GE(culled.culling.mean_holding_per_tile(), 1.0) << "the unranged light holds every tile";
  ShadeOptions unculled;
  unculled.culling = Culling::none;
  const ErrorStats same =
      shading_error(culled.image, shader.shade(scene, gbuffer, unculled).image, testing::shaded_mask(gbuffer));
  EXPECT_LE(same.max_rel, 1e-5) << describe_worst(same);
  const ErrorStats exact = shading_error(culled.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
  EXPECT_LE(exact.max_rel, kRelativeBound) << describe_worst(exact);
}

// A wide spot's bounding sphere reaches far outside its cone: a 140-degree spot 2.5 above the floor
// of the default scene, aimed up, lights none of it, though its sphere (centred 0.34 of the range
// above it, 0.94 of the range across) reaches the floor and the spheres; no tile may keep it. Aimed
// down, tiles keep it where it lights and the image is the unculled one.
TEST(Lights, TiledCullingDropsTilesOutsideASpotsCone) {
  PHONGCL_REQUIRE_DEVICE(shader);
  Scene scene = load_scene(std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes/default/scene.json");
  scene.camera.width = 160;
  scene.camera.height = 120;
  const GBuffer gbuffer = generate_gbuffer(scene);
  Light spot{LightType::spot, {0.0, 2.5, 0.0}, {0.0, 1.0, 0.0}, glm::dvec3(3.0)};
  spot.cone_angle_deg = 140.0;
  spot.range = 6.0;
  scene.lights = {spot};
  ShadeOptions tiled;
  tiled.culling = Culling::tiled;
  const ShadeResult up = shader.shade(scene, gbuffer, tiled);
  EXPECT_GT(up.culling.shaded_tiles, 0u);
  EXPECT_EQ(up.culling.list_entries, 0.0) << "aimed up, it reaches no tile";

  scene.lights[0].direction = {0.0, -1.0, 0.0};
  const ShadeResult down = shader.shade(scene, gbuffer, tiled);
  EXPECT_GT(down.culling.list_entries, 0.0) << "aimed down";
  EXPECT_LT(down.culling.list_entries, static_cast<double>(down.culling.shaded_tiles)) << "aimed down";
  ShadeOptions unculled;
  unculled.culling = Culling::none;
  const std::vector<bool> mask = testing::shaded_mask(gbuffer);
  const ErrorStats same = shading_error(down.image, shader.shade(scene, gbuffer, unculled).image, mask);
  EXPECT_LE(same.max_rel, 1e-5) << describe_worst(same);
  const ErrorStats exact = shading_error(down.image, reference_image(scene, gbuffer), mask);
  EXPECT_LE(exact.max_rel, kRelativeBound) << describe_worst(exact);
}

// A tile on the silhouette of a near sphere against a far wall has a box that spans the space
// between them. Eight lights in that gap, on the silhouette's rays halfway in depth, reach neither
// surface (range 1, 12 from the sphere and 15 from the wall), so they are in such boxes but in none of
// the tiles' distance bins: no tile may keep them. The check that they are in the boxes is the
// lights per tile of the same frame with a wall at 16, where the bins span them.
TEST(Lights, TiledCullingDropsLightsBetweenATilesDepths) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto frame = [](double wall_distance) {
    std::ostringstream json;
    json << R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1], "fov_y_deg": 30, "width": 128, "height": 128},
                "ambient": [0, 0, 0], "lights": [], "materials": [{"name": "grey", "kd": [0.5, 0.5, 0.5]}],
                "objects": [{"type": "sphere", "center": [0, 0, -3], "radius": 0.5, "material": 0},
                            {"type": "plane", "normal": [0, 0, 1], "offset": )"
         << -wall_distance << R"(, "material": 0}]})";
    Scene scene = parse_scene(json.str(), "two depths");
    for (int k = 0; k < 8; ++k) {
      const double angle = k * std::numbers::pi / 4.0;
      // On the ray through the sphere's silhouette (sin = 0.5 / 3 off its axis), 15 from the eye.
      const glm::dvec3 toward{std::cos(angle) * 0.5 / 3.0, std::sin(angle) * 0.5 / 3.0, -1.0};
      Light light{LightType::point, 15.0 * glm::normalize(toward), {0.0, 0.0, 1.0}, glm::dvec3(1.0)};
      light.range = 1.0;
      scene.lights.push_back(light);
    }
    return scene;
  };
  ShadeOptions tiled;
  tiled.culling = Culling::tiled;
  const Scene far_wall = frame(30.0);
  const GBuffer far_gbuffer = generate_gbuffer(far_wall);
  const ShadeResult between = shader.shade(far_wall, far_gbuffer, tiled);
  EXPECT_GT(between.culling.shaded_tiles, 0u);
  EXPECT_EQ(between.culling.list_entries, 0.0) << "the lights are between the tiles' depths";

  const Scene near_wall = frame(16.0);
  const ShadeResult lit = shader.shade(near_wall, generate_gbuffer(near_wall), tiled);
  EXPECT_GT(lit.culling.list_entries, 0.0) << "a wall within the lights' range";
}

// --- Light groups.

// The diffuse + specular of `scene` lit by the lights of `group` alone (empty: the ungrouped ones),
// area lights too, shaded with terms. The others are blacked out rather than removed, so the kernel
// is the same one: under -cl-fast-relaxed-math, one with other light shapes may round differently.
Image lights_alone(PhongShader& shader, Scene scene, const GBuffer& gbuffer, const ShadeOptions& options,
                   const std::string& group) {
  for (Light& light : scene.lights)
    if (light.group != group) light.color = glm::dvec3(0.0);
  for (AreaLight& light : scene.area_lights)
    if (light.group != group) light.color = glm::dvec3(0.0);
  const ShadeResult result = shader.shade(scene, gbuffer, options);
  Image light = result.terms.diffuse;
  for (std::size_t i = 0; i < light.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) light.pixel(i)[c] += result.terms.specular.pixel(i)[c];
  return light;
}

// Each group's layer is the light of its lights alone (the sums differ in their order only), and
// ambient + the groups + the ungrouped lights add up to the combined image: each layer is rounded
// to float once (g + 3 roundings of non-negative values), 8 ulp of the sum leaves room.
void expect_groups_add_up(PhongShader& shader, const Scene& scene, const GBuffer& gbuffer, const ShadeOptions& options,
                          const std::string& where) {
  const ShadeResult result = shader.shade(scene, gbuffer, options);
  const std::vector<std::string> names = light_groups(scene.lights, scene.area_lights);
  ASSERT_EQ(result.terms.group_names, names) << where;
  ASSERT_EQ(result.terms.groups.size(), names.size()) << where;
  EXPECT_EQ(result.recipe.value("LIGHT_GROUPS"), std::to_string(names.size())) << where;
  const std::vector<bool> mask = testing::shaded_mask(gbuffer);
  for (std::size_t g = 0; g < names.size(); ++g) {
    const Image alone = lights_alone(shader, scene, gbuffer, options, names[g]);
    const ErrorStats same = shading_error(result.terms.groups[g], alone, mask);
    EXPECT_LE(same.max_rel, 1e-5) << where << ", group " << names[g] << ": " << describe_worst(same);
  }
  const Image ungrouped = lights_alone(shader, scene, gbuffer, options, "");
  constexpr double kEightUlp = 8 * 0x1p-24;
  bool any_group = false;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (!mask[i]) continue;
    for (int c = 0; c < 3; ++c) {
      double sum = double(result.terms.ambient.pixel(i)[c]) + ungrouped.pixel(i)[c];
      for (const Image& group : result.terms.groups) {
        sum += group.pixel(i)[c];
        any_group |= group.pixel(i)[c] > 0.0f;
      }
      ASSERT_NEAR(sum, result.image.pixel(i)[c], kEightUlp * sum) << where << ": pixel " << i << ", channel " << c;
    }
    for (const Image& group : result.terms.groups) ASSERT_EQ(group.pixel(i)[3], result.image.pixel(i)[3]) << where;
  }
  EXPECT_TRUE(any_group) << where << ": no group lights a pixel, the sum checks too little";
}

TEST(Lights, GroupsAddUpToTheImageInEveryVariant) {
  PHONGCL_REQUIRE_DEVICE(shader);
  ShapedLightSpec shapes;
  shapes.max_cosine_power = 10.0;
  auto [scene, gbuffer] = shaped_scene({"groups", shapes}, 4242);
  const char* groups[] = {"key", "fill", "", "key", "rim-2"};  // light 2 and those past 4 in none
  for (std::size_t i = 0; i < scene.lights.size() && i < 5; ++i) scene.lights[i].group = groups[i];
  // Area lights in a group of point lights, in one of their own, and in none.
  AreaLight rect;
  rect.position = {0.0, 1.0, 4.0};
  rect.direction = {0.0, 0.0, -1.0};
  rect.size = {1.5, 1.0};
  rect.color = {0.8, 0.7, 0.6};
  rect.group = "key";
  AreaLight disk;
  disk.shape = AreaShape::disk;
  disk.position = {1.5, 3.0, 2.0};
  disk.direction = {-0.3, -1.0, -0.5};
  disk.size = glm::dvec2(1.2);
  disk.color = {0.5, 0.6, 0.9};
  disk.group = "panel";
  AreaLight ungrouped = disk;
  ungrouped.position = {-2.0, 0.5, 3.0};
  ungrouped.direction = {0.5, 0.0, -1.0};
  ungrouped.group.clear();
  scene.area_lights = {rect, disk, ungrouped};
  for (Precision precision : {Precision::precise, Precision::fast, Precision::double_precision}) {
    if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
    for (int lanes : {1, 16}) {
      for (bool specialise : {true, false}) {
        ShadeOptions options;
        options.precision = precision;
        options.lanes = lanes;
        options.specialise = specialise;
        options.write_terms = true;
        expect_groups_add_up(shader, scene, gbuffer, options,
                             to_string(precision) + ", " + std::to_string(lanes) + " lanes" +
                                 (specialise ? "" : ", general kernel"));
      }
    }
  }
}

// With tiled culling a tile's list holds lights of every group in index order.
TEST(Lights, GroupsUnderTiledCulling) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = default_scene_with_many_lights(64, 48, 80, 10.0);
  for (std::size_t i = 0; i < scene.lights.size(); ++i) scene.lights[i].group = i % 3 == 2 ? "" : "g" + std::to_string(i % 3);
  ShadeOptions options;
  options.culling = Culling::tiled;
  options.write_terms = true;
  ASSERT_EQ(shader.shade(scene, gbuffer, options).recipe.value("TILED_CULLING"), "1");
  expect_groups_add_up(shader, scene, gbuffer, options, "tiled");
}

// Groups are layers of the AOVs: without terms the kernel is the one of the scene without groups,
// and so is its image.
TEST(Lights, GroupsWithoutTermsLeaveTheKernelAsItWas) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = random_scene({}, 31);
  Scene grouped = scene;
  grouped.lights[0].group = grouped.lights[3].group = "a";
  const ShadeResult plain = shader.shade(scene, gbuffer, {});
  const ShadeResult without_terms = shader.shade(grouped, gbuffer, {});
  EXPECT_EQ(without_terms.recipe.value("LIGHT_GROUPS"), "0");
  EXPECT_EQ(without_terms.build_options, plain.build_options);
  EXPECT_EQ(without_terms.image.rgba, plain.image.rgba);
  EXPECT_EQ(without_terms.kernel_summary, plain.kernel_summary);
}

}  // namespace
}  // namespace phongcl
