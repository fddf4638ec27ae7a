#pragma once
// The scene's BVH and planes in the kernels' layout (kernels/shadow_layout.h), relative to an eye:
// rebuilt in one pass over the tree when the eye moves, never re-sorted.
#include <vector>

#include <glm/glm.hpp>

#include "geometry/scene_bvh.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

static_assert(sizeof(float) == 4 && sizeof(unsigned int) == 4);
static_assert(sizeof(BvhNode) == 64 && offsetof(BvhNode, hi_x) == 24 && offsetof(BvhNode, first) == 48 &&
              offsetof(BvhNode, kind_count) == 56);
static_assert(sizeof(ShadowPrimitive) == 48 && sizeof(ShadowPlane) == 16 && sizeof(ShadowBounds) == 24);
static_assert(sizeof(ShadowCandidate) == 8 && sizeof(ShadowLight) == 32 && offsetof(ShadowLight, directional) == 12 &&
              offsetof(ShadowLight, half_extent) == 16);
static_assert(sizeof(CullLevel) == 16);
static_assert(sizeof(ScreenMarch) == 96 && offsetof(ScreenMarch, scale_x) == 48 && offsetof(ScreenMarch, width) == 64 &&
              offsetof(ScreenMarch, steps) == 80);
static_assert(sizeof(ShadowFrame) == 112 && offsetof(ShadowFrame, node_count) == 96 &&
              offsetof(ShadowFrame, eye_extent) == 108);

namespace phongcl {

struct DeviceGeometry {
  std::vector<BvhNode> nodes;  // empty when the scene has no bounded shape
  std::vector<ShadowPrimitive> primitives;
  std::vector<ShadowBounds> bounds;  // parallel to primitives
  std::vector<ShadowPlane> planes;
};

DeviceGeometry pack_device_geometry(const SceneBvh& scene, const glm::dvec3& eye);

// The most memory building the shadow geometry of `counts` takes at once, host and device: the
// world-space shapes, the BVH's build arrays and nodes, the packed layout and its device copy.
double shadow_geometry_bytes(const ShapeCounts& counts);

}  // namespace phongcl
