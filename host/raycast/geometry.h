#pragma once
// The scene's objects prepared for casting many rays: nested transforms composed once, their
// inverses and normal matrices precomputed, and a world-space bounding ball where that is cheap.
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

class SceneGeometry {
 public:
  explicit SceneGeometry(const std::vector<Object>& objects);

  // The nearest surface with t > t_min along a world-space ray, comparing world-space distances.
  std::optional<SurfaceHit> nearest_hit(const Ray& ray, double t_min) const;

 private:
  struct Primitive {
    Object shape;  // a sphere, plane (unit normal) or triangle, in its own space
    bool transformed = false;
    glm::dmat4 world_to_object{1.0};
    glm::dmat3 normal_to_world{1.0};  // inverse transpose of the object-to-world linear part
    bool bounded = false;             // planes are not; untransformed spheres are their own bound
    glm::dvec3 bound_center{0.0};
    double bound_radius = 0.0;
  };

  void add(const std::vector<Object>& objects, const glm::dmat4& object_to_world, bool transformed);

  std::vector<Primitive> primitives_;
};

}  // namespace phongcl
