#pragma once
// The scene's objects flattened into world space, once: nested transforms composed, mesh files
// read, every triangle's corners carried to world space (an affine map keeps a ray's t and a
// triangle's barycentrics, so a triangle is the same in either space). Spheres keep their own
// space, where they are round: under a non-uniform scale a sphere is an ellipsoid in the world.
// The G-buffer generator, the shadow BVH and the reference's brute-force shadow rays all start here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace phongcl {

struct ShapeTriangle {
  std::array<std::uint32_t, 3> corners;  // into SceneShapes::vertices, counter-clockwise from the front
  int material;
};

struct ShapeSphere {
  glm::dvec3 center;  // in the sphere's own space
  double radius;
  bool transformed;   // false: own space is world space
  glm::dmat4 world_to_object;
  glm::dmat3 normal_to_world;  // inverse transpose of the object-to-world linear part
  int material;
};

// The points x with dot(normal, x) == offset, world space.
struct ShapePlane {
  glm::dvec3 normal;  // unit length
  double offset;
  int material;
};

// An axis-aligned box; empty (lo > hi) by default.
struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

  void extend(const glm::dvec3& point) { lo = glm::min(lo, point), hi = glm::max(hi, point); }
  void extend(const Box& box) { lo = glm::min(lo, box.lo), hi = glm::max(hi, box.hi); }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
  double half_area() const;  // of the surface; 0 when empty
};

struct SceneShapes {
  std::vector<glm::dvec3> vertices;  // world space
  std::vector<ShapeTriangle> triangles;
  std::vector<ShapeSphere> spheres;
  std::vector<ShapePlane> planes;

  std::array<glm::dvec3, 3> corners(std::size_t triangle) const;
  Box triangle_box(std::size_t triangle) const;
  Box sphere_box(std::size_t sphere) const;  // exact for an ellipsoid under any affine map
  std::size_t bounded_count() const { return triangles.size() + spheres.size(); }
};

// Mesh files are read here (geometry/mesh_file.h; InputError naming the file), each once however
// often it is instanced.
SceneShapes flatten_objects(const std::vector<Object>& objects);

// What flatten_objects would hold, each mesh counted per instance, before any mesh is read whole
// (count_mesh; each file once).
struct ShapeCounts {
  std::uint64_t vertices = 0, triangles = 0, spheres = 0;
  std::uint64_t mesh_instances = 0;
};
ShapeCounts count_shapes(const std::vector<Object>& objects);

}  // namespace phongcl
