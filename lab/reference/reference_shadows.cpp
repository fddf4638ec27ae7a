#include "reference/reference_shadows.h"

#include <algorithm>
#include <cmath>

namespace phongcl {
namespace {

struct Segment {
  glm::dvec3 origin, direction;
  double t_begin, t_end;  // the part of the ray that counts
};

// margin > 0 grows the triangle (barycentrics down to -margin), < 0 shrinks it.
bool meets_triangle(const std::array<glm::dvec3, 3>& v, const Segment& s, double margin) {
  const glm::dvec3 e1 = v[1] - v[0], e2 = v[2] - v[0];
  const glm::dvec3 p = glm::cross(s.direction, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0) return false;
  const glm::dvec3 to_origin = s.origin - v[0];
  const double u = glm::dot(to_origin, p) / det;
  const glm::dvec3 q = glm::cross(to_origin, e1);
  const double w = glm::dot(s.direction, q) / det;
  const double t = glm::dot(e2, q) / det;
  return u >= -margin && w >= -margin && u + w <= 1.0 + margin && t > s.t_begin && t < s.t_end;
}

// The sphere's surface, radius scaled by 1 + margin, crossed within the segment.
bool meets_sphere(const ShapeSphere& sphere, const Segment& s, double margin) {
  const glm::dvec3 o = glm::dvec3(sphere.world_to_object * glm::dvec4(s.origin, 1.0)) - sphere.center;
  const glm::dvec3 d = glm::dmat3(sphere.world_to_object) * s.direction;
  const double radius = sphere.radius * (1.0 + margin);
  const double a = glm::dot(d, d), half_b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius;
  const double discriminant = half_b * half_b - a * c;
  if (discriminant < 0.0) return false;
  const double root = std::sqrt(discriminant);
  const double near = (-half_b - root) / a, far = (-half_b + root) / a;
  return (near > s.t_begin && near < s.t_end) || (far > s.t_begin && far < s.t_end);
}

// Crossing the plane between the segment's ends; a plane `thickness` thick when it is > 0 (a
// segment reaching into the slab counts), thinned to nothing but a crossing with both ends
// further than -thickness when it is < 0.
bool meets_plane(const ShapePlane& plane, const Segment& s, double thickness) {
  const double begin = glm::dot(plane.normal, s.origin + s.t_begin * s.direction) - plane.offset;
  const double end = glm::dot(plane.normal, s.origin + s.t_end * s.direction) - plane.offset;
  if (thickness >= 0.0) return (begin > 0.0) != (end > 0.0) || std::min(std::abs(begin), std::abs(end)) <= thickness;
  return (begin > 0.0) != (end > 0.0) && std::min(std::abs(begin), std::abs(end)) > -thickness;
}

bool blocked(const SceneShapes& shapes, const Segment& s, double margin, double thickness) {
  for (std::size_t i = 0; i < shapes.triangles.size(); ++i)
    if (meets_triangle(shapes.corners(i), s, margin)) return true;
  for (const ShapeSphere& sphere : shapes.spheres)
    if (meets_sphere(sphere, s, margin)) return true;
  for (const ShapePlane& plane : shapes.planes)
    if (meets_plane(plane, s, thickness)) return true;
  return false;
}

double largest_magnitude(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

RayOutcome reference_shadow_ray(const SceneShapes& shapes, const glm::dvec3& origin, const glm::dvec3& direction,
                                double t_max, const ShadowSlack& slack) {
  const double length = glm::length(direction);
  const double dt = length > 0.0 ? slack.distance / length : 0.0;
  const Segment grown{origin, direction, -dt, t_max + dt};
  const bool blocked_grown = blocked(shapes, grown, slack.relative, slack.distance);
  if (slack.relative == 0.0 && slack.distance == 0.0) return blocked_grown ? RayOutcome::blocked : RayOutcome::free;
  if (!blocked_grown) return RayOutcome::free;
  const Segment shrunk{origin, direction, dt, t_max - dt};
  return blocked(shapes, shrunk, -slack.relative, -slack.distance) ? RayOutcome::blocked : RayOutcome::borderline;
}

bool reference_shadow_ray_from(const glm::dvec3& position, const glm::dvec3& normal, const Light& light,
                               const glm::dvec3& eye, double offset_scale, ReferenceShadowRay& ray) {
  const double normal_length = glm::length(normal);
  if (!(normal_length > 0.0)) return false;
  const glm::dvec3 n = normal / normal_length;
  const double eye_extent = largest_magnitude(eye);
  const glm::dvec3 origin = position + offset_scale * (largest_magnitude(position - eye) + eye_extent) * n;
  if (light.type == LightType::directional) {
    const glm::dvec3 l = -glm::normalize(light.direction);
    if (!(glm::dot(n, l) > 0.0)) return false;
    ray = {origin, l, 0x1p100};
    return true;
  }
  const glm::dvec3 toward = light.position - position;
  const double distance = glm::length(toward);
  if (!(distance > 0.0) || !(glm::dot(n, toward) > 0.0)) return false;
  const double stop = offset_scale * (largest_magnitude(light.position - eye) + eye_extent);
  ray = {origin, light.position - origin, 1.0 - stop / distance};
  return ray.t_max > 0.0;
}

}  // namespace phongcl
