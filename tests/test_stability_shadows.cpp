// The shadow cases of the stability catalogue (stability/catalogue_shadows.cpp), reference side:
// the brute-force double reference builds each pixel's rays by the specification and decides them
// as the case says, none of them too close to call.
#include <gtest/gtest.h>

#include "cl/device.h"
#include "geometry/device_geometry.h"
#include "geometry/scene_bvh.h"
#include "geometry/scene_shapes.h"
#include "opencl_required.h"
#include "peers/opencl_shadow_rays.h"
#include "peers/packed_frame.h"
#include "reference/reference_shadows.h"
#include "stability/catalogue.h"
#include "temp_dir.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {
namespace {

double largest_magnitude(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

TEST(StabilityShadows, TheReferenceDecidesEveryCaseAsItsGeometrySays) {
  testing::TempDir dir;
  const std::vector<StabilityCase> cases = shadow_cases(dir.path);
  ASSERT_GE(cases.size(), 7u);
  for (const StabilityCase& c : cases) {
    const SceneShapes shapes = flatten_objects(c.scene.objects);
    const glm::dvec3 eye = c.scene.camera.eye;
    std::size_t traced = 0;
    for (std::size_t i = 0; i < c.gbuffer.pixel_count(); ++i) {
      const glm::dvec3 p(c.gbuffer.position[0][i], c.gbuffer.position[1][i], c.gbuffer.position[2][i]);
      const glm::dvec3 n(c.gbuffer.normal[0][i], c.gbuffer.normal[1][i], c.gbuffer.normal[2][i]);
      ASSERT_EQ(c.lit.at(i).size(), c.scene.lights.size()) << c.name;
      for (std::size_t k = 0; k < c.scene.lights.size(); ++k) {
        ReferenceShadowRay ray;
        if (!reference_shadow_ray_from(p, n, c.scene.lights[k], eye, PHONGCL_SHADOW_OFFSET_FLOAT, ray)) continue;
        ++traced;
        // Barycentrics and radii within 2^-20, distances within a quarter of the rays' offset (2^-22
        // against 2^-20 of the same magnitudes), both above the float kernel's rounding.
        const ShadowSlack slack{0x1p-20, 0x1p-22 * (largest_magnitude(ray.origin - eye) + largest_magnitude(eye))};
        const RayOutcome outcome = reference_shadow_ray(shapes, ray.origin, ray.direction, ray.t_max, slack);
        EXPECT_NE(outcome, RayOutcome::borderline) << c.name << ", pixel " << i << ", light " << k;
        EXPECT_EQ(outcome == RayOutcome::blocked, !c.lit[i][k]) << c.name << ", pixel " << i << ", light " << k;
      }
    }
    EXPECT_GT(traced, 0u) << c.name;
  }
}

// The kernel side, through the standalone kernel until shading has shadows: per pixel, as many
// lights blocked as the case says, traversing and culled, in packets of 16 and one ray at a time.
TEST(StabilityShadows, TheKernelsTraversalDecidesEveryCaseAsItsGeometrySays) {
  PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  const ComputeContext compute = make_compute_context(pick_device(""));
  ProgramCache cache{std::filesystem::path()};
  testing::TempDir dir;
  for (const StabilityCase& c : shadow_cases(dir.path)) {
    const glm::dvec3 eye = c.scene.camera.eye;
    const SceneBvh bvh = build_scene_bvh(flatten_objects(c.scene.objects), PHONGCL_BVH_MAX_DEPTH);
    for (int lanes : {16, 1}) {
      OpenClShadowRays tracer(compute, cache, pack_device_geometry(bvh, eye), lanes);
      tracer.set_frame(pack_frame(c.gbuffer, c.scene), c.gbuffer.width, c.gbuffer.height, c.scene, eye,
                       PHONGCL_SHADOW_OFFSET_FLOAT);
      for (auto method : {OpenClShadowRays::Method::traverse, OpenClShadowRays::Method::culled}) {
        const std::vector<float> blocked = tracer.count_blocked(method, 2).blocked_lights;
        for (std::size_t i = 0; i < c.gbuffer.pixel_count(); ++i) {
          const glm::dvec3 p(c.gbuffer.position[0][i], c.gbuffer.position[1][i], c.gbuffer.position[2][i]);
          const glm::dvec3 n(c.gbuffer.normal[0][i], c.gbuffer.normal[1][i], c.gbuffer.normal[2][i]);
          float expected = 0.0f;
          for (std::size_t k = 0; k < c.scene.lights.size(); ++k) {
            ReferenceShadowRay ray;  // only lights facing the pixel are traced
            expected += !c.lit[i][k] && reference_shadow_ray_from(p, n, c.scene.lights[k], eye, PHONGCL_SHADOW_OFFSET_FLOAT, ray);
          }
          EXPECT_EQ(blocked[i], expected) << c.name << ", pixel " << i << ", " << lanes << " lanes, "
                                          << (method == OpenClShadowRays::Method::culled ? "culled" : "traversing");
        }
      }
    }
  }
}

}  // namespace
}  // namespace phongcl
