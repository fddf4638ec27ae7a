#pragma once
// Soft shadows in the reference: the visible fraction of an area light's emitter from a shaded
// point, integrated densely over the emitter by its own rule (a regular grid of cell midpoints, not
// the kernel's lattice), each point decided by the brute-force shadow ray of reference_shadows.h
// and weighted by the diffuse integrand (n.d)(-N.d) / |d|^4 (docs/shadows.md "Soft shadows").
#include <glm/glm.hpp>

#include "geometry/scene_shapes.h"
#include "reference/reference.h"
#include "scene/scene.h"

namespace phongcl {

// The weighted fraction of the emitter's points (grid x grid cells over a rect, the same grid over
// a disk's bounding square keeping the points inside it) whose ray from `point` is free: 1 where no
// point faces `point` and is above its horizon. `eye` and `offset_scale` place the rays' ends as
// the specification does (reference_shadow_ray_from).
double reference_area_visibility(const SceneShapes& shapes, const AreaLight& light, const SurfacePoint& point,
                                 const glm::dvec3& eye, double offset_scale, int grid = 64);

// The same for a light with a size: a sphere light as the disk of its radius through its centre
// facing `point`; a sun as the disk of directions within its angular radius, a disk of radius
// D tan(angle / 2) at distance D along l, D = 1e8 (|point - eye| + 1): its rays' directions differ
// from parallel ones by under 1e-7 of the scene's extent over D.
double reference_light_visibility(const SceneShapes& shapes, const Light& light, const SurfacePoint& point,
                                  const glm::dvec3& eye, double offset_scale, int grid = 64);

}  // namespace phongcl
