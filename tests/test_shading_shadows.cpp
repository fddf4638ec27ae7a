// Shadows in the shading kernel (kernels/phong.cl with kernels/shadow.h) against the double
// reference: geometry shadows against the brute-force rays of reference_shadows.h, screen-space
// shadows against the march of reference_screen_shadows.h, each pixel shaded by reference_image()
// with those decisions. A pixel where some light's decision is within rounding of a silhouette, a
// ray's end, a depth bound or n.l = 0 is counted as borderline and left out (it must be rare).
// Scenes whose lights cast no shadows shade as before, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <phongcl/relighter.hpp>

#include "accuracy_bound.h"
#include "geometry/scene_bvh.h"
#include "raycast/raycast.h"
#include "reference/reference.h"
#include "reference/reference_area.h"
#include "reference/reference_screen_shadows.h"
#include "reference/reference_shadows.h"
#include "shading/shadow_inputs.h"
#include "shadow_test_scene.h"
#include "temp_dir.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {
namespace {

using testing::largest_magnitude;
using testing::TempDir;

// The test scene with every light but the first casting shadows (so a light that does not cast
// them is in every kernel built here too).
Scene casting_scene(const std::filesystem::path& dir, const glm::dvec3& offset, int knot_segments = 48) {
  Scene scene = testing::shadow_test_scene(dir, offset, 96, 72, knot_segments);
  for (Light& light : scene.lights) light.shadows = true;
  scene.lights.front().shadows = false;
  return scene;
}

// Decides one light's reference ray.
using Decide = std::function<RayOutcome(const ReferenceShadowRay&)>;

// The test scene lit also by two rects casting hard shadows from above (one ray to the centre),
// every material's ks 0: the area lights' S is a stated quadrature
// (docs/shading.md "Area lights"), not held to the accuracy bound.
Scene area_casting_scene(const std::filesystem::path& dir) {
  Scene scene = casting_scene(dir, {0, 0, 0});
  for (Material& material : scene.materials) material.ks = glm::dvec3(0.0);
  AreaLight above;
  above.position = {0.5, 4.0, 1.0};
  above.direction = {0.1, -1.0, -0.2};
  above.up = {0.0, 0.0, 1.0};
  above.size = {0.8, 0.5};
  above.color = glm::dvec3(2.0);
  above.shadows = true;
  above.shadow_rays = 1;
  AreaLight side = above;
  side.position = {-3.0, 2.5, 3.0};
  side.direction = {0.7, -0.3, -0.7};
  side.up = {0.0, 1.0, 0.0};
  side.color = glm::dvec3(1.5);
  scene.area_lights = {above, side};
  return scene;
}

struct Expected {
  Image image;
  std::vector<bool> mask;  // shaded pixels with no borderline decision
  std::size_t shaded = 0, borderline = 0, blocked = 0;  // blocked: pixels where some light is
  std::size_t area_blocked = 0;                          // pixels where some area light is
};

Expected reference_with_shadows(const Scene& scene, const GBuffer& gbuffer, const Decide& decide) {
  const glm::dvec3 eye = scene.camera.eye;
  auto ray_from = [&](const SurfacePoint& point, const Light& light, ReferenceShadowRay& ray) {
    return reference_shadow_ray_from(point.position, point.normal, light, eye, PHONGCL_SHADOW_OFFSET_FLOAT, ray);
  };
  Expected expected;
  expected.image = reference_image(scene, gbuffer, [&](const SurfacePoint& point, const Light& light) {
    ReferenceShadowRay ray;
    return !ray_from(point, light, ray) || decide(ray) != RayOutcome::blocked;
  });
  expected.mask.assign(gbuffer.pixel_count(), false);
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
    ++expected.shaded;
    const SurfacePoint point = reference_surface(scene, gbuffer, i);
    bool close = false, blocked = false, area_blocked = false;
    // An area light's shadow ray is the one of the point light at its centre.
    std::vector<Light> casters = scene.lights;
    for (const AreaLight& light : scene.area_lights) casters.push_back(area_shadow_light(light));
    for (std::size_t k = 0; k < casters.size(); ++k) {
      const Light& light = casters[k];
      if (!light.shadows) continue;
      const glm::dvec3 l = light.type == LightType::directional ? -glm::normalize(light.direction)
                                                                : glm::normalize(light.position - point.position);
      // Within float rounding of n.l = 0 the kernel and the reference may decide apart whether to trace.
      close = close || std::abs(glm::dot(glm::normalize(point.normal), l)) < 1e-5;
      ReferenceShadowRay ray;
      if (!ray_from(point, light, ray)) continue;
      const RayOutcome outcome = decide(ray);
      close = close || outcome == RayOutcome::borderline;
      blocked = blocked || outcome == RayOutcome::blocked;
      area_blocked = area_blocked || (outcome == RayOutcome::blocked && k >= scene.lights.size());
    }
    expected.borderline += close;
    expected.blocked += blocked && !close;
    expected.area_blocked += area_blocked && !close;
    expected.mask[i] = !close;
  }
  return expected;
}

// `culled`: whether the frame's geometry shadows are to be culled per tile (the report says so).
Image shade(const Scene& scene, const GBuffer& gbuffer, const ShadowSettings& shadows, int lanes = 0,
            bool culled = true) {
  RelighterOptions options;
  options.lanes = lanes;
  options.shadows = shadows;
  Relighter relighter(scene, gbuffer, options);
  Image image = relighter.shade();
  if (shadows.mode == ShadowMode::geometry) {
    EXPECT_EQ(relighter.last_report().shadows.find("culled in 32x32 tiles") != std::string::npos, culled)
        << relighter.last_report().shadows;
  }
  return image;
}

void expect_agreement(const Image& got, const Expected& expected) {
  const ErrorStats error = testing::shading_error(got, expected.image, expected.mask);
  EXPECT_LE(error.max_rel, testing::kRelativeBound)
      << "worst pixel (" << error.worst_x << ", " << error.worst_y << ") channel " << error.worst_channel;
  EXPECT_LE(expected.borderline, expected.shaded / 100) << expected.borderline << " borderline pixels";
  EXPECT_GT(expected.blocked, expected.shaded / 10);  // shadows are there to get wrong
  std::cout << "[          ] " << expected.shaded << " shaded pixels, " << expected.borderline << " borderline, "
            << expected.blocked << " with a light blocked; max relative error " << error.max_rel << "\n";
}

// Slack for the reference's decisions, as ShadowRays' (test_geometry_shadow_rays.cpp): 2^-20 of
// barycentrics and radii, and in distances 2^-23 of the eye-relative coordinates the kernel
// computes with (the ray's origin plus the farthest shape), below the rays' offset from their
// surfaces (2^-20 of the world coordinates). The kernel's rays differ from the reference's by float
// rounding (2^-22 of the coordinates): a pixel that decision flips is a mismatch the bound catches.
Expected geometry_reference(const Scene& scene, const GBuffer& gbuffer) {
  const SceneBvh bvh = build_scene_bvh(flatten_objects(scene.objects), PHONGCL_BVH_MAX_DEPTH);
  const glm::dvec3 eye = scene.camera.eye;
  const Box& root = bvh.bvh.nodes.at(0).box;
  const double extent = std::max(largest_magnitude(root.lo - eye), largest_magnitude(root.hi - eye));
  return reference_with_shadows(scene, gbuffer, [&](const ReferenceShadowRay& ray) {
    const ShadowSlack slack{0x1p-20, 0x1p-23 * (largest_magnitude(ray.origin - eye) + extent)};
    return reference_shadow_ray(bvh.shapes, ray.origin, ray.direction, ray.t_max, slack);
  });
}

void expect_geometry_matches_reference(const glm::dvec3& offset, int lanes, int knot_segments = 48) {
  TempDir dir;
  const Scene scene = casting_scene(dir.path, offset, knot_segments);
  const GBuffer gbuffer = generate_gbuffer(scene);
  const bool culled = flatten_objects(scene.objects).bounded_count() <= kShadowCullingMaxShapes;
  expect_agreement(shade(scene, gbuffer, {ShadowMode::geometry}, lanes, culled), geometry_reference(scene, gbuffer));
}

// The test scene's few thousand shapes are culled per tile before shading: a ray tests its tile's
// candidates for its light, or nothing where they are none.
TEST(ShadedShadows, GeometryAgreesWithTheBruteForceReference) { expect_geometry_matches_reference({0, 0, 0}, 0); }
TEST(ShadedShadows, GeometryAgreesOnePixelPerWorkItem) { expect_geometry_matches_reference({0, 0, 0}, 1); }
TEST(ShadedShadows, GeometryAMillionUnitsFromTheOriginAgrees) { expect_geometry_matches_reference({1e6, -3e5, 7e5}, 0); }
// A knot of 5,120 triangles is more than culling takes: every ray traverses the BVH.
TEST(ShadedShadows, GeometryOnADenseMeshTraversesAndAgrees) { expect_geometry_matches_reference({0, 0, 0}, 0, 256); }

// Area lights' shadows, decided by the ray to the centre, with the point lights' in one kernel.
TEST(ShadedShadows, AreaLightsInGeometryAgreeWithTheBruteForceReference) {
  TempDir dir;
  const Scene scene = area_casting_scene(dir.path);
  const GBuffer gbuffer = generate_gbuffer(scene);
  const Expected expected = geometry_reference(scene, gbuffer);
  EXPECT_GT(expected.area_blocked, expected.shaded / 20) << "area lights' shadows are there to get wrong";
  expect_agreement(shade(scene, gbuffer, {ShadowMode::geometry}), expected);
}

// The march's decisions within 2^-16 of a depth bound or 2^-9 of a pixel's edge are borderline
// (float pixel coordinates near 100 carry ~1e-5 px).
void expect_screen_matches_reference(const ShadowSettings& settings, bool area_lights = false) {
  TempDir dir;
  const Scene scene = area_lights ? area_casting_scene(dir.path) : casting_scene(dir.path, {0, 0, 0});
  const GBuffer gbuffer = generate_gbuffer(scene);
  const ReferenceScreenMarch march(scene.camera, gbuffer, settings.steps, settings.thickness);
  const Expected expected = reference_with_shadows(
      scene, gbuffer, [&](const ReferenceShadowRay& ray) { return march.march(ray, 0x1p-16, 0x1p-9); });
  if (area_lights) {
    EXPECT_GT(expected.area_blocked, expected.shaded / 20) << "area lights' shadows are there to get wrong";
  }
  expect_agreement(shade(scene, gbuffer, settings), expected);
}

TEST(ShadedShadows, ScreenAgreesWithTheReferenceMarch) { expect_screen_matches_reference({ShadowMode::screen, 32, -0.06}); }
TEST(ShadedShadows, ScreenInWorldThicknessAgreesWithTheReferenceMarch) {
  expect_screen_matches_reference({ShadowMode::screen, 8, 0.4});
}
TEST(ShadedShadows, AreaLightsInScreenSpaceAgreeWithTheReferenceMarch) {
  expect_screen_matches_reference({ShadowMode::screen, 32, -0.06}, true);
}

bool same_bits(const Image& a, const Image& b) {
  return a.rgba.size() == b.rgba.size() && std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

// With shadows compiled in, a light whose rays are all free adds exactly what it adds without: the
// visibility is a select, never a product.
TEST(ShadedShadows, FreeRaysChangeNoBit) {
  TempDir dir;
  Scene scene = casting_scene(dir.path, {0, 0, 0});
  const GBuffer gbuffer = generate_gbuffer(scene);
  Object behind;  // behind the camera: it blocks nothing the camera sees
  behind.kind = Object::Kind::sphere;
  behind.center = scene.camera.eye + 3.0 * (scene.camera.eye - scene.camera.look_at);
  behind.radius = 0.1;
  scene.objects = {behind};
  RelighterOptions options;
  options.shadows.mode = ShadowMode::geometry;
  Relighter shadowed(scene, gbuffer, options);
  EXPECT_NE(shadowed.build_options().find("-DSHADOWS=1"), std::string::npos);
  options.shadows.mode = ShadowMode::off;
  Relighter unshadowed(scene, gbuffer, options);
  EXPECT_NE(unshadowed.build_options().find("-DSHADOWS=0"), std::string::npos);
  EXPECT_TRUE(same_bits(shadowed.shade(), unshadowed.shade()));
}

// Culling keeps the tiles' boxes of shaded positions while the packed G-buffer is kept: moved
// lights are culled against the same boxes, a moved eye packs the G-buffer again and takes new
// ones. Either way the frame is what a new relighter shades.
TEST(ShadedShadows, CulledShadowsFollowMovedLightsAndAMovedEye) {
  TempDir dir;
  Scene scene = casting_scene(dir.path, {0, 0, 0});
  const GBuffer gbuffer = generate_gbuffer(scene);
  RelighterOptions options;
  options.shadows.mode = ShadowMode::geometry;
  Relighter relighter(scene, gbuffer, options);
  const Image before = relighter.shade();
  for (Light& light : scene.lights) light.position += glm::dvec3(0.4, 0.3, -0.2);
  relighter.set_lights(scene.lights);
  const Image moved_lights = relighter.shade();
  EXPECT_FALSE(same_bits(moved_lights, before));
  EXPECT_TRUE(same_bits(moved_lights, Relighter(scene, gbuffer, options).shade()));
  scene.camera.eye += glm::dvec3(0.5, 0.2, 0.0);
  relighter.set_camera_eye(scene.camera.eye);
  EXPECT_TRUE(same_bits(relighter.shade(), Relighter(scene, gbuffer, options).shade()));
}

TEST(ShadedShadows, TheModeFollowsTheSceneAndTheLights) {
  TempDir dir;
  Scene scene = casting_scene(dir.path, {0, 0, 0});
  const GBuffer gbuffer = generate_gbuffer(scene);
  auto options_for = [](ShadowMode mode) {
    RelighterOptions options;
    options.shadows.mode = mode;
    return options;
  };
  EXPECT_NE(Relighter(scene, gbuffer, options_for(ShadowMode::automatic)).kernel_summary().find("geometry shadows (4 lights)"),
            std::string::npos);
  for (Light& light : scene.lights) light.shadows = false;
  EXPECT_NE(Relighter(scene, gbuffer).build_options().find("-DSHADOWS=0"), std::string::npos);
  scene.lights.back().shadows = true;
  scene.objects.clear();  // a renderer's G-buffer alone: screen space is all there is
  EXPECT_NE(Relighter(scene, gbuffer, options_for(ShadowMode::automatic)).build_options().find("-DSCREEN_SHADOWS=1"),
            std::string::npos);
  EXPECT_THROW(Relighter(scene, gbuffer, options_for(ShadowMode::geometry)), std::invalid_argument);
  RelighterOptions bad = options_for(ShadowMode::screen);
  bad.shadows.steps = 0;
  EXPECT_THROW(Relighter(scene, gbuffer, bad), std::invalid_argument);
}

}  // namespace
}  // namespace phongcl
