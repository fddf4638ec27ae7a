// kernels/shadow.h and kernels/bvh.h through kernels/shadow_rays.cl: the rays are the specification's
// (the double reference builds them independently from the same G-buffer), and every ray's decision
// is the brute-force double reference's wherever that decision is not within rounding of a
// silhouette or an end (borderline rays are counted, and must be rare). With Embree installed, the
// Embree peer is held to the same reference on the same rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>

#include "cl/device.h"
#include "geometry/device_geometry.h"
#include "geometry/scene_bvh.h"
#include "opencl_required.h"
#include "peers/light_sweep.h"
#include "peers/opencl_shadow_rays.h"
#include "peers/packed_frame.h"
#include "raycast/raycast.h"
#include "reference/reference_screen_shadows.h"
#include "reference/reference_shadows.h"
#include "shading/screen_depth.h"
#include "shadow_test_scene.h"
#include "temp_dir.h"
#ifdef PHONGCL_HAVE_EMBREE
#include "embree/embree_peer.h"
#endif

namespace phongcl {
namespace {

using testing::TempDir;
using testing::largest_magnitude;
using testing::shadow_test_scene;

struct Device {
  ComputeContext compute;
  ProgramCache cache{std::filesystem::path()};
};

Device* shared_device() {
  static std::unique_ptr<Device> device;
  static bool tried = false;
  if (!tried) {
    tried = true;
    if (!list_devices().empty()) device.reset(new Device{make_compute_context(pick_device("")), ProgramCache(std::filesystem::path())});
  }
  return device.get();
}

#define REQUIRE_DEVICE(name)                                                 \
  Device* name = shared_device();                                            \
  PHONGCL_REQUIRE_OPENCL(name != nullptr)

// A scene's G-buffer (ray-cast), its BVH, and the standalone kernel holding both and the frame.
struct Traced {
  Scene scene;
  GBuffer gbuffer;
  glm::dvec3 eye;
  SceneBvh bvh;
  OpenClShadowRays tracer;
  Traced(Device& device, Scene lit, int lanes)
      : scene(std::move(lit)),
        gbuffer(generate_gbuffer(scene)),
        eye(scene.camera.eye),
        bvh(build_scene_bvh(flatten_objects(scene.objects), PHONGCL_BVH_MAX_DEPTH)),
        tracer(device.compute, device.cache, pack_device_geometry(bvh, eye), lanes) {
    tracer.set_frame(pack_frame(gbuffer, scene), gbuffer.width, gbuffer.height, scene, eye, PHONGCL_SHADOW_OFFSET_FLOAT);
  }
};

struct Agreement {
  std::size_t rays = 0, borderline = 0, disagree = 0;
};

// The reference's outcome for every ray. Slack: 2^-20 of barycentrics and radii, and in distances
// 2^-23 of the eye-relative coordinates the kernel computes with (the ray's origin plus the
// farthest shape): above float's rounding of the same tests (2^-24 of them, over a few
// operations), below the rays' offset from their surfaces (2^-20 of the world coordinates).
std::vector<RayOutcome> reference_outcomes(const SceneBvh& scene, const glm::dvec3& eye, const ShadowRaySet& rays) {
  const Box& root = scene.bvh.nodes.at(0).box;
  const double extent = std::max(largest_magnitude(root.lo - eye), largest_magnitude(root.hi - eye));
  std::vector<RayOutcome> outcomes(rays.size, RayOutcome::free);
  for (std::size_t i = 0; i < rays.size; ++i) {
    if (!(rays.t_max[i] > 0.0f)) continue;
    const glm::dvec3 origin = eye + glm::dvec3(rays.ox[i], rays.oy[i], rays.oz[i]);
    const glm::dvec3 direction(rays.dx[i], rays.dy[i], rays.dz[i]);
    const ShadowSlack slack{0x1p-20, 0x1p-23 * (largest_magnitude(origin - eye) + extent)};
    outcomes[i] = reference_shadow_ray(scene.shapes, origin, direction, rays.t_max[i], slack);
  }
  return outcomes;
}

Agreement compare(const std::vector<RayOutcome>& reference, const ShadowRaySet& rays, const std::vector<float>& blocked,
                  const glm::dvec3& eye) {
  Agreement agreement;
  for (std::size_t i = 0; i < rays.size; ++i) {
    if (!(rays.t_max[i] > 0.0f)) continue;
    ++agreement.rays;
    if (reference[i] == RayOutcome::borderline) {
      ++agreement.borderline;
    } else if ((reference[i] == RayOutcome::blocked) != (blocked[i] != 0.0f)) {
      if (++agreement.disagree <= 5)
        ADD_FAILURE() << "ray " << i << " from " << rays.ox[i] + eye.x << ", " << rays.oy[i] + eye.y << ", "
                      << rays.oz[i] + eye.z << " along " << rays.dx[i] << ", " << rays.dy[i] << ", " << rays.dz[i]
                      << " to t = " << rays.t_max[i] << ": reference "
                      << (reference[i] == RayOutcome::blocked ? "blocked" : "free") << ", traced "
                      << (blocked[i] != 0.0f ? "blocked" : "free");
    }
  }
  return agreement;
}

void expect_kernel_matches_reference(const glm::dvec3& offset, int lanes) {
  REQUIRE_DEVICE(device);
  TempDir dir;
  Traced traced(*device, shadow_test_scene(dir.path, offset, 96, 72), lanes);
  auto& [scene, gbuffer, eye, bvh, tracer] = traced;
  const ShadowRaySet rays = tracer.make_rays();
  const std::vector<float> traversed = tracer.trace(rays);
  const Agreement agreement = compare(reference_outcomes(bvh, eye, rays), rays, traversed, eye);
  EXPECT_EQ(agreement.disagree, 0u);
  // Every light in one work-item, as shading meets them, with or without tiled culling, which only
  // leaves out what cannot block: per pixel, as many blocked lights as the rays one by one.
  const std::size_t stride = rays.size / scene.lights.size();
  std::vector<float> expected(stride, 0.0f);
  for (std::size_t i = 0; i < rays.size; ++i) expected[i % stride] += traversed[i];
  for (int tile_size : {0, 16, 5}) {
    const OpenClShadowRays::Counts culled = tracer.count_blocked(
        tile_size == 0 ? OpenClShadowRays::Method::traverse : OpenClShadowRays::Method::culled, std::max(tile_size, 1));
    std::size_t differ = 0;
    for (std::size_t i = 0; i < stride; ++i) differ += culled.blocked_lights[i] != expected[i];
    EXPECT_EQ(differ, 0u) << "tiles of " << tile_size;
    // ... and does leave things out: at 5 x 5 pixels (a 96 x 72 frame) most pairs have a short list.
    if (tile_size != 5) continue;
    EXPECT_LT(culled.traversing_pairs, 0.2);
    EXPECT_LT(culled.candidates_per_pair, 8.0);
  }
  EXPECT_GT(agreement.rays, 10000u);
  // Grazing rays along the ground and past silhouettes: a few in ten thousand at most.
  EXPECT_LE(agreement.borderline, agreement.rays / 2000) << agreement.borderline << " of " << agreement.rays;
  std::cout << "[          ] " << agreement.rays << " rays, " << agreement.borderline << " borderline\n";
}

TEST(ShadowRays, EveryShapeAgreesWithTheBruteForceReferencePacketsOf16) { expect_kernel_matches_reference({0, 0, 0}, 16); }

// The bench's soft rays (16 per pixel; the point lights as spheres, the directional one a sun): a
// point light's rays end on its sphere's facing disk (t = 1 is the point of the emitter), and the
// traversal decides every ray as the reference.
TEST(ShadowRays, SoftRaysEndOnTheEmitterAndAgreeWithTheReference) {
  REQUIRE_DEVICE(device);
  TempDir dir;
  Traced traced(*device, shadow_test_scene(dir.path, {0, 0, 0}, 48, 36), 16);
  auto& [scene, gbuffer, eye, bvh, tracer] = traced;
  constexpr float kRadius = 0.3f;
  constexpr int kRays = 16;
  const ShadowRaySet hard = tracer.make_rays();
  const ShadowRaySet rays = tracer.make_soft_rays(kRadius, kRays);
  ASSERT_EQ(rays.size, hard.size * kRays);
  const std::size_t frame = hard.size / scene.lights.size();
  double farthest = 0.0;
  for (std::size_t i = 0; i < rays.size; ++i) {
    if (!(rays.t_max[i] > 0.0f)) continue;
    const Light& light = scene.lights[i / frame / kRays];
    if (light.type == LightType::directional) continue;
    const glm::dvec3 end = eye + glm::dvec3(rays.ox[i] + rays.dx[i], rays.oy[i] + rays.dy[i], rays.oz[i] + rays.dz[i]);
    farthest = std::max(farthest, glm::length(end - light.position));
  }
  // Float rounding of eye-relative points a few units from the eye: far below a millimetre.
  EXPECT_LE(farthest, kRadius * (1.0 + 1e-4));
  EXPECT_GT(farthest, kRadius * 0.9) << "the rays spread over the disk";
  EXPECT_GT(rays.traced(), hard.traced() * kRays / 2);
  const Agreement agreement = compare(reference_outcomes(bvh, eye, rays), rays, tracer.trace(rays), eye);
  EXPECT_EQ(agreement.disagree, 0u);
  EXPECT_LE(agreement.borderline, agreement.rays / 2000) << agreement.borderline << " of " << agreement.rays;
}
TEST(ShadowRays, EveryShapeAgreesWithTheBruteForceReferenceOneRayPerWorkItem) { expect_kernel_matches_reference({0, 0, 0}, 1); }
TEST(ShadowRays, AMillionUnitsFromTheOriginAgreesToo) { expect_kernel_matches_reference({1e6, -3e5, 7e5}, 16); }

// Tiled culling on many shapes (scenes/large's spheres, 16 lights): a tile's list is filtered from its
// parent's, and a parent's run of a leaf's primitives splits where some of them miss the tile, so a
// tile may need more entries than its parent holds. It must then traverse, never write past its
// room into the next pair's list: every tile size leaves each pixel's count of blocked lights as
// the traversal's. (At the scene's own 1920x1080, 514 pixels differed in tiles of 16 when a list
// could outgrow its room; at 960x540 none did.)
// A level quad of two triangles whose shared diagonal crosses the frame, from half size 1e4 to 1e30
// (the scene reader's bound): rays from the ground below it, on the diagonal and within a few units
// of it (a corner 1e8 out is rounded by 8 in float), all end above it and are all blocked: no ray
// slips between the triangles, and none of their products overflows.
TEST(ShadowRays, RaysThroughAHugeQuadsSharedEdgeAreAllBlocked) {
  REQUIRE_DEVICE(device);
  const glm::dvec3 eye(0.3, 2, 10);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> along(-5, 5), beside(-4, 4);
  for (double half : {1e4, 1e8, 1e12, 1e19, 1e30}) {
    const glm::dvec3 a(-half, 1, -half), b(half, 1, -half), c(half, 1, half), d(-half, 1, half);
    Object first{.kind = Object::Kind::triangle, .vertices = {a, b, c}}, second{.kind = Object::Kind::triangle, .vertices = {a, c, d}};
    const SceneBvh bvh = build_scene_bvh(flatten_objects({first, second}), PHONGCL_BVH_MAX_DEPTH);
    ShadowRaySet rays;
    rays.size = 1024;
    for (auto* plane : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.t_max}) plane->resize(rays.size);
    for (std::size_t i = 0; i < rays.size; ++i) {
      const double x = along(random), off = i % 2 == 0 ? 0.0 : beside(random) * (i % 4 == 1 ? 1.0 : 1e-3);
      const glm::dvec3 origin(x + off, 0, x - off);
      // Toward a light 5 above, or a sun low along x (its ray reaches the quad's plane within 3 units).
      const bool sun = i % 3 == 0;
      const glm::dvec3 direction = sun ? glm::normalize(glm::dvec3(1, 0.4, -0.3)) : glm::dvec3(0.4, 5, -0.3);
      rays.ox[i] = static_cast<float>(origin.x - eye.x), rays.oy[i] = static_cast<float>(origin.y - eye.y);
      rays.oz[i] = static_cast<float>(origin.z - eye.z);
      rays.dx[i] = static_cast<float>(direction.x), rays.dy[i] = static_cast<float>(direction.y);
      rays.dz[i] = static_cast<float>(direction.z), rays.t_max[i] = sun ? 0x1p100f : 1.0f;
    }
    for (int lanes : {16, 1}) {
      OpenClShadowRays tracer(device->compute, device->cache, pack_device_geometry(bvh, eye), lanes);
      const std::vector<float> blocked = tracer.trace(rays);
      EXPECT_EQ(std::count(blocked.begin(), blocked.end(), 0.0f), 0) << "half size " << half << ", " << lanes << " lanes";
    }
  }
}

TEST(ShadowRays, TiledCullingOnManyShapesLeavesEveryCountAsTheTraversals) {
  REQUIRE_DEVICE(device);
  const Scene scene = with_generated_lights(load_scene(std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes/large/scene.json"), 16);
  Traced traced(*device, scene, 16);
  const std::vector<float> traversed = traced.tracer.count_blocked(OpenClShadowRays::Method::traverse).blocked_lights;
  for (int tile_size : {8, 16, 32}) {
    const std::vector<float> culled =
        traced.tracer.count_blocked(OpenClShadowRays::Method::culled, tile_size).blocked_lights;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < traversed.size(); ++i) differ += culled[i] != traversed[i];
    EXPECT_EQ(differ, 0u) << "tiles of " << tile_size;
  }
}

// The kernel builds the specification's rays: from the reference's own double construction out of
// the same G-buffer, within float rounding.
TEST(ShadowRays, RaysAreTheSpecificationsWithinFloatRounding) {
  REQUIRE_DEVICE(device);
  TempDir dir;
  Traced traced(*device, shadow_test_scene(dir.path, {0, 0, 0}, 40, 30), 16);
  auto& [scene, gbuffer, eye, bvh, tracer] = traced;
  const std::size_t stride = pack_frame(gbuffer, scene).px.size();
  const ShadowRaySet rays = tracer.make_rays();
  std::size_t checked = 0;
  for (std::size_t k = 0; k < scene.lights.size(); ++k) {
    for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
      if (gbuffer.material[i] < 0) continue;
      const glm::dvec3 p(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]);
      const glm::dvec3 n(gbuffer.normal[0][i], gbuffer.normal[1][i], gbuffer.normal[2][i]);
      ReferenceShadowRay expected;
      const bool made = reference_shadow_ray_from(p, n, scene.lights[k], eye, PHONGCL_SHADOW_OFFSET_FLOAT, expected);
      const std::size_t slot = k * stride + i;
      // Within float rounding of n.l = 0 either may decide; elsewhere both make the ray or neither.
      const glm::dvec3 l = scene.lights[k].type == LightType::directional ? -glm::normalize(scene.lights[k].direction)
                                                                          : glm::normalize(scene.lights[k].position - p);
      if (std::abs(glm::dot(glm::normalize(n), l)) < 1e-5) continue;
      ASSERT_EQ(made, rays.t_max[slot] > 0.0f) << "pixel " << i << ", light " << k;
      if (!made) continue;
      ++checked;
      const double scale = largest_magnitude(p - eye) + largest_magnitude(eye);
      const glm::dvec3 origin = eye + glm::dvec3(rays.ox[slot], rays.oy[slot], rays.oz[slot]);
      EXPECT_LE(largest_magnitude(origin - expected.origin), 4 * 0x1p-24 * scale) << "pixel " << i;
      const glm::dvec3 direction(rays.dx[slot], rays.dy[slot], rays.dz[slot]);
      EXPECT_LE(largest_magnitude(direction - expected.direction), 4 * 0x1p-24 * (largest_magnitude(expected.direction) + scale));
      EXPECT_NEAR(rays.t_max[slot], expected.t_max, 4 * 0x1p-24 * expected.t_max);
    }
  }
  EXPECT_GT(checked, 2000u);
}

// The screen-space march against the double reference's (reference_screen_shadows.h), pixel by
// pixel: as many blocked lights, wherever no light's decision is within rounding of a bound
// (2^-16 of a depth, 2^-9 of a pixel: float's pixel coordinates near 100 carry ~1e-5 px).
void expect_march_matches_reference(int steps, float thickness) {
  REQUIRE_DEVICE(device);
  TempDir dir;
  Traced traced(*device, shadow_test_scene(dir.path, {0, 0, 0}, 96, 72), 16);
  auto& [scene, gbuffer, eye, bvh, tracer] = traced;
  const ScreenDepth screen = screen_depth(scene.camera, gbuffer, steps, thickness);
  const std::vector<float> blocked = tracer.count_blocked(OpenClShadowRays::Method::screen, 16, &screen).blocked_lights;
  const ReferenceScreenMarch reference(scene.camera, gbuffer, steps, thickness);
  std::size_t compared = 0, borderline = 0, blocked_somewhere = 0;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (gbuffer.material[i] < 0) continue;
    const glm::dvec3 p(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]);
    const glm::dvec3 n(gbuffer.normal[0][i], gbuffer.normal[1][i], gbuffer.normal[2][i]);
    float expected = 0.0f;
    bool close = false;
    for (const Light& light : scene.lights) {
      ReferenceShadowRay ray;
      if (!reference_shadow_ray_from(p, n, light, eye, PHONGCL_SHADOW_OFFSET_FLOAT, ray)) continue;
      const RayOutcome outcome = reference.march(ray, 0x1p-16, 0x1p-9);
      close = close || outcome == RayOutcome::borderline;
      expected += outcome == RayOutcome::blocked;
    }
    if (close) {
      ++borderline;
      continue;
    }
    ++compared;
    blocked_somewhere += expected > 0.0f;
    EXPECT_EQ(blocked[i], expected) << "pixel " << i % gbuffer.width << ", " << i / gbuffer.width;
  }
  EXPECT_LT(borderline, compared / 50) << borderline << " borderline pixels";
  EXPECT_GT(blocked_somewhere, compared / 10);  // the march does find shadows here
  std::cout << "[          ] " << compared << " pixels, " << borderline << " borderline, " << blocked_somewhere
            << " with a light blocked\n";
}

TEST(ShadowRays, ScreenMarchAgreesWithTheReference) { expect_march_matches_reference(32, -0.06f); }
TEST(ShadowRays, ScreenMarchInWorldThicknessAgreesWithTheReference) { expect_march_matches_reference(8, 0.4f); }
TEST(ShadowRays, ScreenMarchWithThicknessFromTheStepAgreesWithTheReference) { expect_march_matches_reference(64, 0.0f); }

#ifdef PHONGCL_HAVE_EMBREE
TEST(ShadowRays, EmbreeAgreesWithTheReferenceOnTheSameRays) {
  REQUIRE_DEVICE(device);
  TempDir dir;
  Scene knot = knot_scene(dir.path, 64, 12, 3);
  knot.camera.width = 160;
  knot.camera.height = 120;
  Traced traced(*device, std::move(knot), 16);
  auto& [scene, gbuffer, eye, bvh, tracer] = traced;
  const ShadowRaySet rays = tracer.make_rays();
  const EmbreeShadowPeer embree(bvh.shapes, eye);
  const std::vector<RayOutcome> reference = reference_outcomes(bvh, eye, rays);
  for (EmbreeApi api : {EmbreeApi::packet16, EmbreeApi::single}) {
    const Agreement agreement = compare(reference, rays, embree.trace(rays, api), eye);
    EXPECT_EQ(agreement.disagree, 0u) << to_string(api);
    EXPECT_GT(agreement.rays, 20000u);
    EXPECT_LE(agreement.borderline, agreement.rays / 2000);
  }
  EXPECT_EQ(compare(reference, rays, tracer.trace(rays), eye).disagree, 0u);
}

TEST(ShadowRays, EmbreeRefusesShapesItDoesNotHave) {
  Object ball;
  ball.kind = Object::Kind::sphere;
  EXPECT_THROW(EmbreeShadowPeer(flatten_objects({ball}), glm::dvec3(0.0)), std::invalid_argument);
}
#endif

}  // namespace
}  // namespace phongcl
