#pragma once
// The scene's objects prepared for casting many rays: nested transforms composed once, their
// inverses and normal matrices precomputed, and a world-space bounding ball for every bounded
// primitive, so blocks of rays can skip what they cannot hit.
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "raycast/camera.h"
#include "scene/scene.h"

namespace phongcl {

struct SurfaceHit {
  double t;
  glm::dvec3 normal;  // unit length, world space, either side
  int material;
};

struct BoundingBall {
  glm::dvec3 center;
  double radius;
};

class SceneGeometry {
 public:
  explicit SceneGeometry(const std::vector<Object>& objects);

  // Indices of the primitives a ray inside `frustum` may hit (planes always).
  std::vector<std::size_t> candidates(const Frustum& frustum) const;

  // The nearest of `candidates` with t > t_min along a world-space ray, comparing world distances.
  std::optional<SurfaceHit> nearest_hit(const Ray& ray, double t_min,
                                        const std::vector<std::size_t>& candidates) const;

 private:
  struct Primitive {
    Object shape;  // a sphere, plane (unit normal) or triangle, in its own space
    bool transformed = false;
    glm::dmat4 world_to_object{1.0};
    glm::dmat3 normal_to_world{1.0};  // inverse transpose of the object-to-world linear part
    std::optional<BoundingBall> bound;  // world space; planes have none
    bool test_bound_per_ray = false;  // cheaper than the exact test (not so for a plain sphere)
  };

  void add(const std::vector<Object>& objects, const glm::dmat4& object_to_world, bool transformed);

  std::vector<Primitive> primitives_;
};

}  // namespace phongcl
