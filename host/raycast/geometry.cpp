#include "raycast/geometry.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace phongcl {
namespace {

// The deepest tree the traversal's fixed stack below holds.
constexpr int kMaxDepth = 64;

// The parameter interval (t_near, t_far) in which the ray is inside the box, clipped to
// (t_min, t_max); empty when t_near > t_far. An axis the ray runs parallel to clips nothing when
// the origin is within the slab and everything when it is not.
std::pair<double, double> box_interval(const Box& box, const Ray& ray, double t_min, double t_max) {
  double t_near = t_min, t_far = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    if (ray.direction[axis] == 0.0) {
      if (ray.origin[axis] < box.lo[axis] || ray.origin[axis] > box.hi[axis]) return {1.0, 0.0};
      continue;
    }
    const double inverse = 1.0 / ray.direction[axis];
    double t0 = (box.lo[axis] - ray.origin[axis]) * inverse, t1 = (box.hi[axis] - ray.origin[axis]) * inverse;
    if (t0 > t1) std::swap(t0, t1);
    t_near = std::max(t_near, t0);
    t_far = std::min(t_far, t1);
  }
  return {t_near, t_far};
}

}  // namespace

SceneGeometry::SceneGeometry(const std::vector<Object>& objects)
    : scene_(build_scene_bvh(flatten_objects(objects), kMaxDepth)) {}

int SceneGeometry::material_of(std::uint32_t item) const {
  const SceneShapes& shapes = scene_.shapes;
  return scene_.group(item) == ShapeGroup::triangle ? shapes.triangles[item].material
                                                    : shapes.spheres[item - shapes.triangles.size()].material;
}

std::optional<PrimitiveHit> SceneGeometry::intersect_item(std::uint32_t item, const Ray& ray, double t_min,
                                                          double t_max) const {
  const SceneShapes& shapes = scene_.shapes;
  if (scene_.group(item) == ShapeGroup::triangle) return intersect_triangle(ray, shapes.corners(item), t_min, t_max);
  const ShapeSphere& sphere = shapes.spheres[item - shapes.triangles.size()];
  if (!sphere.transformed) return intersect_sphere(ray, sphere.center, sphere.radius, t_min, t_max);
  // An affine map keeps t: the object-space point at t is the image of the world point at t.
  const Ray local{glm::dvec3(sphere.world_to_object * glm::dvec4(ray.origin, 1.0)),
                  glm::dmat3(sphere.world_to_object) * ray.direction};
  std::optional<PrimitiveHit> hit = intersect_sphere(local, sphere.center, sphere.radius, t_min, t_max);
  if (hit) hit->normal = glm::normalize(sphere.normal_to_world * hit->normal);
  return hit;
}

std::optional<SurfaceHit> SceneGeometry::nearest_hit(const Ray& ray, double t_min) const {
  std::optional<SurfaceHit> nearest;
  double t_max = std::numeric_limits<double>::infinity();
  for (const ShapePlane& plane : scene_.shapes.planes) {
    if (auto hit = intersect_plane(ray, plane.normal, plane.offset, t_min, t_max)) {
      t_max = hit->t;
      nearest = SurfaceHit{hit->t, hit->normal, plane.material};
    }
  }
  const std::vector<Bvh::Node>& nodes = scene_.bvh.nodes;
  if (nodes.empty()) return nearest;
  std::array<std::uint32_t, kMaxDepth + 1> stack;
  int size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const Bvh::Node& node = nodes[stack[--size]];
    const auto [t_near, t_far] = box_interval(node.box, ray, t_min, t_max);
    if (t_near > t_far) continue;
    if (!node.leaf()) {
      // Nearer child on top, so that its hits shorten the ray before the other is visited.
      const std::uint32_t first = node.first;
      const bool second_nearer = box_interval(nodes[first + 1].box, ray, t_min, t_max).first <
                                 box_interval(nodes[first].box, ray, t_min, t_max).first;
      stack[size++] = second_nearer ? first : first + 1;
      stack[size++] = second_nearer ? first + 1 : first;
      continue;
    }
    for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
      const std::uint32_t item = scene_.bvh.order[i];
      if (auto hit = intersect_item(item, ray, t_min, t_max)) {
        t_max = hit->t;
        nearest = SurfaceHit{hit->t, hit->normal, material_of(item)};
      }
    }
  }
  return nearest;
}

}  // namespace phongcl
