// The environment light: its scene entry, its map's validation and irradiance convolution
// (host/environment/), and the kernel (kernels/environment.h) against the brute-force reference
// (lab/reference/reference_environment.h), unoccluded and with geometry visibility.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "environment/equirect_map.h"
#include "environment_maps.h"
#include "environment/irradiance_map.h"
#include "exr/exr_channels.h"
#include "geometry/scene_shapes.h"
#include "input_error_of.h"
#include "raycast/raycast.h"
#include "reference/reference_environment.h"
#include "shading_support.h"
#include "temp_dir.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {
namespace {

using std::numbers::pi;

using testing::gradient_texel;
using testing::sky_texel;
using testing::write_map;

Scene scene_with(const std::string& light_json, const std::filesystem::path& source) {
  return parse_scene(R"({"lights": [)" + light_json + R"(], "materials": [{"name": "m", "kd": [1, 1, 1]}]})", source);
}

TEST(EnvironmentScene, ReadsAUniformWorldAndAMapBesideTheScene) {
  const Scene uniform = scene_with(R"({"type": "environment", "color": [0.2, 0.3, 0.4], "strength": 2, "group": "sky"})",
                                   "/scenes/a.json");
  ASSERT_TRUE(uniform.environment);
  EXPECT_EQ(uniform.environment->color, glm::dvec3(0.2, 0.3, 0.4));
  EXPECT_EQ(uniform.environment->strength, 2.0);
  EXPECT_TRUE(uniform.environment->shadows);  // visible as in Cycles unless asked
  EXPECT_TRUE(uniform.lights.empty());
  EXPECT_EQ(light_groups(uniform.lights, uniform.area_lights, uniform.environment), std::vector<std::string>{"sky"});
  const Scene map = scene_with(R"({"type": "environment", "file": "sky.exr", "rotation": 30, "rays": 8, "shadows": false})",
                               "/scenes/a.json");
  EXPECT_EQ(map.environment->file, std::filesystem::path("/scenes/sky.exr"));
  EXPECT_EQ(map.environment->rotation_deg, 30.0);
  EXPECT_EQ(map.environment->rays, 8);
  EXPECT_FALSE(map.environment->shadows);
}

TEST(EnvironmentScene, RefusesASecondWorldAndAmbiguousOnes) {
  const std::string two = testing::input_error_of([] {
    scene_with(R"({"type": "environment", "color": [1, 1, 1]}, {"type": "environment", "file": "b.exr"})", "two.json");
  });
  EXPECT_NE(two.find("two.json"), std::string::npos) << two;
  EXPECT_NE(two.find("lights[1]"), std::string::npos) << two;
  EXPECT_NE(two.find("second environment"), std::string::npos) << two;
  const std::string both = testing::input_error_of(
      [] { scene_with(R"({"type": "environment", "color": [1, 1, 1], "file": "b.exr"})", "both.json"); });
  EXPECT_NE(both.find("not both"), std::string::npos) << both;
  const std::string negative = testing::input_error_of(
      [] { scene_with(R"({"type": "environment", "color": [1, -1, 1]})", "negative.json"); });
  EXPECT_NE(negative.find("must be >= 0"), std::string::npos) << negative;
}

TEST(EnvironmentMap, RefusesInfiniteAndNaNTexelsNamingThem) {
  testing::TempDir dir;
  for (double bad : {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(), -1.0}) {
    const auto file = write_map(dir.path / "bad.exr", 16, 8, [&](int x, int y) {
      return x == 5 && y == 3 ? glm::dvec3(0.5, bad, 0.5) : glm::dvec3(0.5);
    });
    const std::string message = testing::input_error_of([&] { load_radiance_grid(file); });
    EXPECT_NE(message.find("bad.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("texel (5, 3) channel G is " +
                           std::string(std::isnan(bad) ? "NaN" : std::isinf(bad) ? "inf" : "negative")),
              std::string::npos)
        << message;
  }
  const std::string missing = testing::input_error_of([&] { load_radiance_grid(dir.path / "none.exr"); });
  EXPECT_NE(missing.find("none.exr"), std::string::npos) << missing;
}

// A 1 x 1 map is a uniform world: E / pi is its colour for every normal. The grid's midpoint rule
// over 256 x 128 cells integrates the clamped cosine to 1.3e-5 (measured; the kink at the horizon
// cuts cells, an error of order the cell's width squared).
// A map is read 256 rows at a time (a 16k map's memory, scripts/checks/69-environment-memory.sh): the
// grid is the one its whole planes give, and read_rows() of blocks that cut across the ZIP file's
// 16-row chunks gives the rows read() gives.
TEST(EnvironmentMap, ABlockOfRowsAtATimeReadsTheWholeMap) {
  testing::TempDir dir;
  const int width = 300, height = 600;
  const auto texel = [&](int x, int y) { return sky_texel(x, y, width, height) * (1.0 + 0.001 * (x % 7)); };
  const auto file = write_map(dir.path / "tall.exr", width, height, texel);
  std::vector<float> planes[3];
  exr::InputExr exr(file);
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(static_cast<std::size_t>(width) * height);
    exr.read({{std::string(1, "RGB"[c]), planes[c].data()}});
  }
  EXPECT_EQ(load_radiance_grid(file).rgb,
            radiance_grid_from_planes(file, width, height, {planes[0].data(), planes[1].data(), planes[2].data()}).rgb);
  const int block = 7;  // across the chunks' boundaries
  std::vector<float> rows(static_cast<std::size_t>(width) * block);
  for (int first = 0; first < height; first += block) {
    const int count = std::min(block, height - first);
    exr.read_rows({{"G", rows.data()}}, first, count);
    ASSERT_TRUE(std::equal(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(count) * width,
                           planes[1].begin() + static_cast<std::ptrdiff_t>(first) * width))
        << "rows " << first << " to " << first + count - 1;
  }
}

TEST(EnvironmentMap, AOneTexelMapIsAUniformWorld) {
  const float texel[3] = {0.25f, 0.5f, 1.0f};
  const RadianceGrid grid = radiance_grid_from_planes("one", 1, 1, {&texel[0], &texel[1], &texel[2]});
  const IrradianceMap irradiance = convolve_irradiance(grid);
  double worst = 0.0;
  for (std::size_t i = 0; i < irradiance.rgb.size(); ++i)
    worst = std::max(worst, std::abs(irradiance.rgb[i] / texel[i % 3] - 1.0));
  std::cout << "[          ] 1x1 map: worst relative error of E/pi over the irradiance map " << worst << "\n";
  EXPECT_LE(worst, 5e-5);
}

// The convolution at the irradiance map's normals, plus the suns taken out of it, against the brute
// force over every texel: the same integral over the same cells (the map is finer than neither
// grid), so only summation order and float storage differ. The sun texel is 2 x 2 cells of the grid,
// each over 1% of the power: taken out as four suns.
TEST(EnvironmentMap, ConvolutionMatchesTheBruteForceAtItsNormals) {
  testing::TempDir dir;
  const int width = 128, height = 64;
  EnvironmentLight light;
  light.file = write_map(dir.path / "sky.exr", width, height, [&](int x, int y) { return sky_texel(x, y, width, height); });
  const IrradianceMap irradiance = convolve_irradiance(load_radiance_grid(light.file));
  const ReferenceMap& map = reference_map(light);
  double worst = 0.0;
  for (int y = 0; y < irradiance.height; y += 3)
    for (int x = 0; x < irradiance.width; x += 5) {
      const glm::dvec3 n = equirect_direction((x + 0.5) / irradiance.width, (y + 0.5) / irradiance.height);
      const glm::dvec3 want = reference_environment_light(light, map, n);
      glm::dvec3 suns(0.0);
      for (const EnvironmentSunCell& sun : irradiance.suns) suns += sun.color * std::max(0.0, glm::dot(n, sun.direction));
      for (int c = 0; c < 3; ++c) {
        const double got = irradiance.rgb[3 * (static_cast<std::size_t>(y) * irradiance.width + x) + c] + suns[c];
        worst = std::max(worst, std::abs(got - want[c]) / std::max(want[c], 1e-3));
      }
    }
  std::cout << "[          ] sky with a sun texel: convolution against brute force, worst relative " << worst << "\n";
  EXPECT_EQ(irradiance.suns.size(), 4u);
  EXPECT_LE(worst, 1e-5);
}

// Every shaded pixel of a random G-buffer lit by the environment alone, kernel against reference.
ErrorStats environment_error(PhongShader& shader, const Scene& scene, const GBuffer& gbuffer, const char* what) {
  ShadeOptions options;
  options.shadows.mode = ShadowMode::off;
  const ShadeResult result = shader.shade(scene, gbuffer, options);
  EXPECT_NE(result.build_options.find("-DENVIRONMENT=1"), std::string::npos);
  const ErrorStats error =
      compare_images(result.image, reference_image(scene, gbuffer), 1e-3, testing::shaded_mask(gbuffer));
  std::cout << "[          ] " << what << ": " << testing::describe_worst(error) << "\n";
  return error;
}

// Diffuse materials (ks 0: the specular's own tests are test_environment_specular.cpp).
std::pair<Scene, GBuffer> environment_only(unsigned seed) {
  testing::RandomSceneSpec spec;
  spec.point_lights = spec.directional_lights = 0;
  auto [scene, gbuffer] = testing::random_scene(spec, seed);
  scene.ambient = glm::dvec3(0.0);
  for (Material& material : scene.materials) material.ks = glm::dvec3(0.0);
  return {scene, gbuffer};
}

TEST(EnvironmentShading, AUniformWorldLightsKdTimesItsColour) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = environment_only(71);
  scene.environment = EnvironmentLight{};
  scene.environment->color = {0.3, 0.6, 0.9};
  scene.environment->strength = 1.5;
  // The kernel's kd C s is exact to a few roundings; the reference's midpoint rule over 256 x 128
  // cells is 3.3e-5 off for a uniform world (AOneTexelMapIsAUniformWorld).
  EXPECT_LE(environment_error(shader, scene, gbuffer, "uniform world").max_rel, 5e-5);
}

// The bilinear lookup between the irradiance map's normals is the approximation: 2.9e-4 worst
// (relative, 1e-3 floor) measured on the sky whose sun (16 cells of the grid) comes as directional
// lights; left in the map it was 0.30 off at the sun's horizon. The reference integrates every
// texel for each pixel.
TEST(EnvironmentShading, AMapAgreesWithTheBruteForceReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  testing::TempDir dir;
  auto [scene, gbuffer] = environment_only(72);
  const int width = 64, height = 32;
  scene.environment = EnvironmentLight{};
  scene.environment->file = write_map(dir.path / "sky.exr", width, height, [&](int x, int y) { return sky_texel(x, y, width, height); });
  for (double rotation : {0.0, 75.0}) {
    scene.environment->rotation_deg = rotation;
    scene.environment->strength = 0.5;
    const ErrorStats error = environment_error(shader, scene, gbuffer, rotation == 0.0 ? "sky, rotation 0" : "sky, rotation 75");
    EXPECT_LE(error.max_rel, 1e-3);
  }
}

// The mapping's orientation: a map bright in one texel column only lights normals facing it. The
// middle column faces +X (Cycles' equirectangular mapping); rotation r turns the lookup by +r about Z.
TEST(EnvironmentShading, TheMiddleColumnLooksAlongPlusX) {
  testing::TempDir dir;
  EnvironmentLight light;
  light.file = write_map(dir.path / "column.exr", 64, 32, [](int x, int) { return glm::dvec3(x == 32 || x == 31 ? 1.0 : 0.0); });
  const IrradianceMap irradiance = convolve_irradiance(load_radiance_grid(light.file));
  auto at = [&](double u) { return irradiance.rgb[3 * (static_cast<std::size_t>(irradiance.height / 2) * irradiance.width +
                                                       static_cast<std::size_t>(u * irradiance.width))]; };
  EXPECT_GT(at(0.5), 10.0f * at(0.0));  // the middle faces the bright column, the edge faces away
  EXPECT_NEAR(glm::length(equirect_direction(0.5, 0.5) - glm::dvec3(1, 0, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(equirect_direction(0.75, 0.5) - glm::dvec3(0, -1, 0)), 0.0, 1e-12);
  const ReferenceMap& map = reference_map(light);
  light.rotation_deg = 90.0;  // the lookup along +Y is turned to -X: away from the column
  EXPECT_LT(reference_environment_light(light, map, {0, 1, 0}).x, 0.1 * reference_environment_light(light, map, {0, -1, 0}).x);
}

// A floor and a sphere resting on it under a uniform white world.
Scene sphere_on_floor() {
  Scene scene;
  scene.camera.eye = {0.0, 4.0, 6.0};
  scene.camera.look_at = {0.0, 0.4, 0.0};
  scene.camera.width = 40;
  scene.camera.height = 30;
  Material grey;
  grey.kd = glm::dvec3(0.8);
  scene.materials = {grey};
  Object floor, ball;
  floor.kind = Object::Kind::plane;
  floor.normal = {0, 1, 0};
  ball.kind = Object::Kind::sphere;
  ball.center = {-0.5, 0.8, 0.0};
  ball.radius = 0.8;
  scene.objects = {floor, ball};
  scene.environment = EnvironmentLight{};
  scene.environment->color = glm::dvec3(1.0);
  return scene;
}

// The reference's image of the scene's environment light, every texel's direction traced from each pixel.
Image reference_visible_image(const Scene& scene, const GBuffer& gbuffer, const SceneShapes& shapes) {
  const EnvironmentLight& world = *scene.environment;
  SoftVisibility visibility;
  visibility.environment = [&](const SurfacePoint& point) {
    return reference_environment_visible_light(world, reference_map(world), shapes, point, scene.camera.eye,
                                               PHONGCL_SHADOW_OFFSET_FLOAT);
  };
  return reference_image(scene, gbuffer, {}, visibility);
}

// The kernel's visible light against the reference's, which traces every texel's direction: under
// a uniform world and under a sky whose zenith is 12 times brighter than its ground, where what a
// blocked ray takes away depends on where it points. Each blocked ray takes the sky's light in its
// direction away: a fraction 1/N of the pixel's unoccluded light where the sky is uniform, so that
// from N rays of a 0/1 visibility the rms over the image is at most 1/(2 sqrt N) of it; the
// gradient's zenith, brighter than its average, doubles that bound. Unbiased, the error falls as
// 1/sqrt N: 16 times the rays make it 4 times smaller, held to 3 (a bias leaves a floor: the
// visible fraction times the unoccluded light stopped at 2.5 under the sky).
TEST(EnvironmentShading, GeometryVisibilityAgreesWithTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  testing::TempDir dir;
  Scene scene = sphere_on_floor();
  const GBuffer gbuffer = generate_gbuffer(scene);
  const SceneShapes shapes = flatten_objects(scene.objects);
  const int width = 64, height = 32;
  const auto sky = write_map(dir.path / "sky.exr", width, height, [&](int, int y) { return gradient_texel(y, height); });
  for (const bool uniform : {true, false}) {
    if (!uniform) scene.environment->file = sky;
    const EnvironmentLight& world = *scene.environment;
    const Image reference = reference_visible_image(scene, gbuffer, shapes);
    std::vector<double> rms_at;
    for (int rays : {16, 256}) {
      ShadeOptions options;
      options.shadows.mode = ShadowMode::geometry;
      options.shadows.environment_rays = rays;
      const ShadeResult result = shader.shade(scene, gbuffer, options);
      EXPECT_NE(result.build_options.find("-DENVIRONMENT_SHADOWS=1"), std::string::npos);
      double sum_sq = 0.0;
      std::size_t count = 0, occluded = 0;
      for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
        if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
        const SurfacePoint point = reference_surface(scene, gbuffer, i);
        const double unoccluded = 0.8 * reference_environment_light(world, reference_map(world), point.normal).x;
        const double difference = (result.image.pixel(i)[0] - reference.pixel(i)[0]) / unoccluded;
        sum_sq += difference * difference;
        occluded += reference.pixel(i)[0] < 0.95 * unoccluded;
        ++count;
      }
      const double rms = std::sqrt(sum_sq / static_cast<double>(count));
      std::cout << "[          ] " << (uniform ? "uniform world, " : "sky, ") << rays << " rays: against the reference over "
                << count << " pixels (" << occluded << " under 95% of their unoccluded light): rms " << rms << "\n";
      EXPECT_GT(occluded, count / 10) << "occlusion to get wrong";
      EXPECT_LE(rms, (uniform ? 1.0 : 2.0) / (2.0 * std::sqrt(static_cast<double>(rays))));
      rms_at.push_back(rms);
    }
    EXPECT_GE(rms_at[0] / rms_at[1], 3.0) << (uniform ? "uniform world" : "sky") << ": the error stopped falling with rays";
  }
}

// Screen space (kernels/environment_horizons.h) sees only what the camera sees, each surface 6% of
// its depth deep: the ground far behind the sphere takes the sphere's samples for a slab reaching
// towards it (4% to 6% too dark in the top rows), and the 40 x 30 image gives each slice few pixels.
// Held to the reference's visible light at its measured level less a margin: within 5% of the
// pixels' unoccluded light on 88.4% of them under the uniform world (held to 85%) and 94.1% under
// the sky (90%), rms 0.041 and 0.036 (held to 0.05). A floor alone blocks nothing: its own samples
// lie in its tangent plane, so every pixel gets its unoccluded light but for rounding.
TEST(EnvironmentShading, ScreenSpaceVisibilityAgreesWithTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  testing::TempDir dir;
  Scene scene = sphere_on_floor();
  const int width = 64, height = 32;
  const auto sky = write_map(dir.path / "sky.exr", width, height, [&](int, int y) { return gradient_texel(y, height); });
  ShadeOptions options;
  options.shadows.mode = ShadowMode::screen;
  options.shadows.environment_rays = 64;
  for (const bool uniform : {true, false}) {
    if (!uniform) scene.environment->file = sky;
    const GBuffer gbuffer = generate_gbuffer(scene);
    const SceneShapes shapes = flatten_objects(scene.objects);
    const EnvironmentLight& world = *scene.environment;
    const Image reference = reference_visible_image(scene, gbuffer, shapes);
    const ShadeResult result = shader.shade(scene, gbuffer, options);
    EXPECT_NE(result.build_options.find("-DSCREEN_SHADOWS=1"), std::string::npos);
    double sum_sq = 0.0;
    std::size_t count = 0, within = 0;
    for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
      if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
      const SurfacePoint point = reference_surface(scene, gbuffer, i);
      const double unoccluded = 0.8 * reference_environment_light(world, reference_map(world), point.normal).x;
      const double difference = (result.image.pixel(i)[0] - reference.pixel(i)[0]) / unoccluded;
      sum_sq += difference * difference;
      within += std::abs(difference) <= 0.05;
      ++count;
    }
    const double rms = std::sqrt(sum_sq / static_cast<double>(count));
    const double agreement = static_cast<double>(within) / static_cast<double>(count);
    std::cout << "[          ] screen space, " << (uniform ? "uniform world" : "sky") << ", 64 slices: against the reference over "
              << count << " pixels: " << 100.0 * agreement << "% within 5%, rms " << rms << "\n";
    EXPECT_GE(agreement, uniform ? 0.85 : 0.90);
    EXPECT_LE(rms, 0.05);
  }

  scene.objects.pop_back();  // the floor alone
  const GBuffer gbuffer = generate_gbuffer(scene);
  const Image open = shader.shade(scene, gbuffer, options).image;
  options.shadows.mode = ShadowMode::off;
  const Image unoccluded = shader.shade(scene, gbuffer, options).image;
  double worst = 0.0, sum = 0.0;
  std::size_t worst_pixel = 0, shaded = 0;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
    const double off = 1.0 - open.pixel(i)[0] / unoccluded.pixel(i)[0];
    if (std::abs(off) > worst) worst = std::abs(off), worst_pixel = i;
    sum += off;
    ++shaded;
  }
  const double mean = sum / static_cast<double>(shaded);
  std::cout << "[          ] screen space, the floor alone: " << 100.0 * mean << "% of its light taken on average; worst pixel ("
            << worst_pixel % gbuffer.width << ", " << worst_pixel / gbuffer.width << ") " << worst << " off it\n";
  EXPECT_LE(mean, 0.03);
  EXPECT_LE(worst, 0.06);
}

TEST(EnvironmentShading, CompiledOutWithoutAnEnvironment) {
  PHONGCL_REQUIRE_DEVICE(shader);
  auto [scene, gbuffer] = environment_only(73);
  scene.lights.push_back({LightType::directional, {}, {0, -1, 0}, glm::dvec3(1.0)});
  const ShadeResult result = shader.shade(scene, gbuffer, ShadeOptions{});
  EXPECT_NE(result.build_options.find("-DENVIRONMENT=0"), std::string::npos) << result.build_options;
  EXPECT_NE(result.build_options.find("-DENVIRONMENT_SHADOWS=0"), std::string::npos) << result.build_options;
}

}  // namespace
}  // namespace phongcl
