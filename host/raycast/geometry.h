#pragma once
// The scene's objects prepared for casting many rays: flattened into world space once
// (geometry/scene_shapes.h, mesh files read there) under a BVH (geometry/bvh.h), so a ray visits
// the few shapes near it whatever the scene's size.
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/scene_bvh.h"
#include "raycast/camera.h"
#include "raycast/intersect.h"
#include "scene/scene.h"

namespace phongcl {

struct SurfaceHit {
  double t;
  glm::dvec3 normal;  // unit length, world space, either side
  int material;
};

class SceneGeometry {
 public:
  explicit SceneGeometry(const std::vector<Object>& objects);

  // The nearest shape with t_min < t along a world-space ray.
  std::optional<SurfaceHit> nearest_hit(const Ray& ray, double t_min) const;

 private:
  // BVH item `item` (scene_bvh.h) between t_min and t_max, its normal in world space.
  std::optional<PrimitiveHit> intersect_item(std::uint32_t item, const Ray& ray, double t_min, double t_max) const;
  int material_of(std::uint32_t item) const;

  SceneBvh scene_;
};

}  // namespace phongcl
