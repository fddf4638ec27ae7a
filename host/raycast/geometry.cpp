#include "raycast/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "raycast/intersect.h"

namespace phongcl {
namespace {

// The primitive's bounding ball in its own space: exact for a sphere, about the centroid for a
// triangle.
BoundingBall object_space_bound(const Object& shape) {
  if (shape.kind == Object::Kind::sphere) return {shape.center, shape.radius};
  const auto& v = shape.vertices;
  const glm::dvec3 centroid = (v[0] + v[1] + v[2]) / 3.0;
  return {centroid, std::max({glm::length(v[0] - centroid), glm::length(v[1] - centroid),
                              glm::length(v[2] - centroid)})};
}

// A linear map stretches lengths by at most its largest singular value, which the Frobenius norm
// bounds; loose for anisotropic scales, but a bound only ever skips work.
double max_stretch(const glm::dmat3& linear) {
  return std::sqrt(glm::dot(linear[0], linear[0]) + glm::dot(linear[1], linear[1]) +
                   glm::dot(linear[2], linear[2]));
}

std::optional<PrimitiveHit> intersect_shape(const Object& shape, const Ray& ray, double t_min, double t_max) {
  switch (shape.kind) {
    case Object::Kind::sphere: return intersect_sphere(ray, shape.center, shape.radius, t_min, t_max);
    case Object::Kind::plane: return intersect_plane(ray, shape.normal, shape.offset, t_min, t_max);
    case Object::Kind::triangle: return intersect_triangle(ray, shape.vertices, t_min, t_max);
    case Object::Kind::transform: break;  // flattened away in add()
  }
  return std::nullopt;
}

}  // namespace

SceneGeometry::SceneGeometry(const std::vector<Object>& objects) { add(objects, glm::dmat4(1.0), false); }

void SceneGeometry::add(const std::vector<Object>& objects, const glm::dmat4& object_to_world,
                        bool transformed) {
  for (const Object& object : objects) {
    if (object.kind == Object::Kind::transform) {
      add(object.children, object_to_world * object.matrix, true);
      continue;
    }
    Primitive primitive;
    primitive.shape = object;
    if (object.kind == Object::Kind::plane) primitive.shape.normal = glm::normalize(object.normal);
    primitive.transformed = transformed;
    const glm::dmat3 linear(object_to_world);
    primitive.world_to_object = glm::inverse(object_to_world);
    primitive.normal_to_world = glm::transpose(glm::inverse(linear));
    if (object.kind != Object::Kind::plane) {
      const BoundingBall ball = object_space_bound(object);
      primitive.bound = BoundingBall{glm::dvec3(object_to_world * glm::dvec4(ball.center, 1.0)),
                                     ball.radius * (transformed ? max_stretch(linear) : 1.0)};
      primitive.test_bound_per_ray = transformed || object.kind == Object::Kind::triangle;
    }
    primitives_.push_back(std::move(primitive));
  }
}

std::vector<std::size_t> SceneGeometry::candidates(const Frustum& frustum) const {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const std::optional<BoundingBall>& bound = primitives_[i].bound;
    if (!bound || frustum.may_overlap_ball(bound->center, bound->radius)) indices.push_back(i);
  }
  return indices;
}

std::optional<SurfaceHit> SceneGeometry::nearest_hit(const Ray& ray, double t_min,
                                                     const std::vector<std::size_t>& candidates) const {
  std::optional<SurfaceHit> nearest;
  double t_max = std::numeric_limits<double>::infinity();
  for (std::size_t index : candidates) {
    const Primitive& primitive = primitives_[index];
    if (primitive.test_bound_per_ray &&
        !ray_meets_ball(ray, primitive.bound->center, primitive.bound->radius, t_min, t_max))
      continue;
    // An affine map keeps t: the object-space point at t is the image of the world point at t.
    const Ray local = primitive.transformed
                          ? Ray{glm::dvec3(primitive.world_to_object * glm::dvec4(ray.origin, 1.0)),
                                glm::dmat3(primitive.world_to_object) * ray.direction}
                          : ray;
    const std::optional<PrimitiveHit> hit = intersect_shape(primitive.shape, local, t_min, t_max);
    if (!hit) continue;
    t_max = hit->t;
    const glm::dvec3 normal =
        primitive.transformed ? glm::normalize(primitive.normal_to_world * hit->normal) : hit->normal;
    nearest = SurfaceHit{hit->t, normal, primitive.shape.material};
  }
  return nearest;
}

}  // namespace phongcl
