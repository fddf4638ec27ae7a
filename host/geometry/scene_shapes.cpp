#include "geometry/scene_shapes.h"

#include <cmath>
#include <map>

#include "geometry/mesh_file.h"

namespace phongcl {
namespace {

class Flattener {
 public:
  explicit Flattener(SceneShapes& shapes) : shapes_(shapes) {}

  void add(const std::vector<Object>& objects, const glm::dmat4& object_to_world, bool transformed) {
    for (const Object& object : objects) {
      switch (object.kind) {
        case Object::Kind::transform: add(object.children, object_to_world * object.matrix, true); break;
        case Object::Kind::sphere: add_sphere(object, object_to_world, transformed); break;
        case Object::Kind::plane: add_plane(object, object_to_world); break;
        case Object::Kind::triangle: add_triangles(object.vertices, {{{0, 1, 2}}}, object_to_world, object.material); break;
        case Object::Kind::mesh: add_mesh(object, object_to_world); break;
      }
    }
  }

 private:
  template <typename Points>
  void add_triangles(const Points& points, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                     const glm::dmat4& object_to_world, int material) {
    const auto base = static_cast<std::uint32_t>(shapes_.vertices.size());
    for (const auto& point : points) shapes_.vertices.push_back(glm::dvec3(object_to_world * glm::dvec4(glm::dvec3(point), 1.0)));
    for (const auto& corners : triangles)
      shapes_.triangles.push_back({{base + corners[0], base + corners[1], base + corners[2]}, material});
  }

  void add_mesh(const Object& object, const glm::dmat4& object_to_world) {
    auto [entry, inserted] = meshes_.try_emplace(object.file);
    if (inserted) entry->second = read_mesh(object.file);
    add_triangles(entry->second.vertices, entry->second.triangles, object_to_world, object.material);
  }

  void add_sphere(const Object& object, const glm::dmat4& object_to_world, bool transformed) {
    shapes_.spheres.push_back({object.center, object.radius, transformed, glm::inverse(object_to_world),
                               glm::transpose(glm::inverse(glm::dmat3(object_to_world))), object.material});
  }

  // The image of a plane under an affine map is a plane: through the image of one of its points,
  // normal to the normal's image under the inverse transpose.
  void add_plane(const Object& object, const glm::dmat4& object_to_world) {
    const glm::dvec3 unit = glm::normalize(object.normal);
    const glm::dvec3 point = glm::dvec3(object_to_world * glm::dvec4(unit * object.offset, 1.0));
    const glm::dvec3 normal = glm::normalize(glm::transpose(glm::inverse(glm::dmat3(object_to_world))) * unit);
    shapes_.planes.push_back({normal, glm::dot(normal, point), object.material});
  }

  SceneShapes& shapes_;
  std::map<std::filesystem::path, TriangleMesh> meshes_;
};

void count_objects(const std::vector<Object>& objects, std::map<std::filesystem::path, MeshCounts>& meshes,
                   ShapeCounts& counts) {
  for (const Object& object : objects) {
    switch (object.kind) {
      case Object::Kind::transform: count_objects(object.children, meshes, counts); break;
      case Object::Kind::sphere: ++counts.spheres; break;
      case Object::Kind::plane: break;
      case Object::Kind::triangle: counts.vertices += 3, ++counts.triangles; break;
      case Object::Kind::mesh: {
        auto [entry, inserted] = meshes.try_emplace(object.file);
        if (inserted) entry->second = count_mesh(object.file);
        counts.vertices += entry->second.vertices;
        counts.triangles += entry->second.triangles;
        ++counts.mesh_instances;
        break;
      }
    }
  }
}

}  // namespace

double Box::half_area() const {
  if (empty()) return 0.0;
  const glm::dvec3 size = hi - lo;
  return size.x * size.y + size.y * size.z + size.z * size.x;
}

std::array<glm::dvec3, 3> SceneShapes::corners(std::size_t triangle) const {
  const auto& index = triangles[triangle].corners;
  return {vertices[index[0]], vertices[index[1]], vertices[index[2]]};
}

Box SceneShapes::triangle_box(std::size_t triangle) const {
  Box box;
  for (const glm::dvec3& corner : corners(triangle)) box.extend(corner);
  return box;
}

// The ellipsoid {M x : |x - c| <= r} reaches r * |row i of M's linear part| either side of M c
// along world axis i.
Box SceneShapes::sphere_box(std::size_t index) const {
  const ShapeSphere& sphere = spheres[index];
  if (!sphere.transformed) return {sphere.center - sphere.radius, sphere.center + sphere.radius};
  const glm::dmat4 object_to_world = glm::inverse(sphere.world_to_object);
  const glm::dvec3 centre = glm::dvec3(object_to_world * glm::dvec4(sphere.center, 1.0));
  glm::dvec3 reach;
  for (int axis = 0; axis < 3; ++axis)
    reach[axis] = sphere.radius * glm::length(glm::dvec3(object_to_world[0][axis], object_to_world[1][axis],
                                                          object_to_world[2][axis]));
  return {centre - reach, centre + reach};
}

ShapeCounts count_shapes(const std::vector<Object>& objects) {
  std::map<std::filesystem::path, MeshCounts> meshes;
  ShapeCounts counts;
  count_objects(objects, meshes, counts);
  return counts;
}

SceneShapes flatten_objects(const std::vector<Object>& objects) {
  SceneShapes shapes;
  Flattener(shapes).add(objects, glm::dmat4(1.0), false);
  return shapes;
}

}  // namespace phongcl
