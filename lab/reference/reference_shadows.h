#pragma once
// Shadow rays in double precision by brute force: every triangle, sphere and plane of the scene
// tested against every ray, no BVH, written from the specification (docs/shadows.md) and sharing
// nothing with kernels/ or the BVH (geometry/bvh.h); the shapes come flattened into world space
// (geometry/scene_shapes.h), as the G-buffer generator also takes them.
#include <glm/glm.hpp>

#include "geometry/scene_shapes.h"
#include "scene/scene.h"

namespace phongcl {

// The margins within which a decision is too close to call: barycentrics and radii `relative`
// (of the triangle, of the radius), distances `distance` (world units: the ray's ends, a plane).
struct ShadowSlack {
  double relative = 0.0;
  double distance = 0.0;
};

enum class RayOutcome { free, blocked, borderline };

// The segment origin + t direction, 0 < t < t_max (world space), decided twice: with every shape
// grown by the slack (the t interval too) and shrunk by it. Blocked both ways: blocked; free both
// ways: free; else borderline (a ray grazing a silhouette, or ending within rounding of a surface).
// With no slack the outcome is never borderline.
RayOutcome reference_shadow_ray(const SceneShapes& shapes, const glm::dvec3& origin, const glm::dvec3& direction,
                                double t_max, const ShadowSlack& slack = {});

// The specification's shadow ray from a shaded point (docs/shadows.md): it leaves P by
// eps(P) = offset_scale (|P - eye|_inf + |eye|_inf) along the unit normal (facing the light) and
// stops eps(L) short of a point or spot light; a directional light's runs to t = 2^100 along l.
// False when the light faces away (n.l <= 0), has no direction (light at P) or the normal is zero.
struct ReferenceShadowRay {
  glm::dvec3 origin, direction;
  double t_max;
};
bool reference_shadow_ray_from(const glm::dvec3& position, const glm::dvec3& normal, const Light& light,
                               const glm::dvec3& eye, double offset_scale, ReferenceShadowRay& ray);

}  // namespace phongcl
