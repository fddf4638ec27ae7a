#pragma once
// The scene's bounded shapes (triangles, then spheres) under one BVH, in world space and double
// precision: built once per scene geometry, whatever the eye or the lights.
#include <cstdint>

#include "geometry/bvh.h"
#include "geometry/scene_shapes.h"

namespace phongcl {

// Item i of the BVH is triangle i for i < triangles.size(), else sphere i - triangles.size().
enum class ShapeGroup : std::uint8_t { triangle = 0, sphere = 1 };

struct SceneBvh {
  SceneShapes shapes;
  Bvh bvh;

  ShapeGroup group(std::uint32_t item) const {
    return item < shapes.triangles.size() ? ShapeGroup::triangle : ShapeGroup::sphere;
  }
};

// max_depth: the deepest tree the traversal's stack allows (kernels/shadow_layout.h).
SceneBvh build_scene_bvh(SceneShapes shapes, int max_depth);

}  // namespace phongcl
