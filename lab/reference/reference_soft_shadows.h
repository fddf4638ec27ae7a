#pragma once
// Soft shadows in the reference: the visible fraction of an area light's emitter from a shaded
// point, integrated densely over the emitter by its own rule (a regular grid of cell midpoints, not
// the kernel's lattice), each point decided by the brute-force shadow ray of reference_shadows.h
// and weighted by the diffuse integrand (n.d)(-N.d) / |d|^4 (docs/shadows.md "Soft shadows").
#include <functional>

#include <glm/glm.hpp>

#include "geometry/scene_shapes.h"
#include "reference/reference.h"
#include "scene/scene.h"

namespace phongcl {

// The weighted fraction of the emitter's points (grid x grid cells over a rect, the same grid over
// a disk's bounding square keeping the points inside it) whose ray from `point` is free: 1 where no
// point faces `point` and is above its horizon. `eye` and `offset_scale` place the rays' ends as
// the specification does (reference_shadow_ray_from).
// `cone`, where set, multiplies each visible point's weight (a spot's cone seen from that point).
double reference_area_visibility(const SceneShapes& shapes, const AreaLight& light, const SurfacePoint& point,
                                 const glm::dvec3& eye, double offset_scale, int grid = 64,
                                 const std::function<double(const glm::dvec3& emitter_point)>& cone = {});

// The same for a light with a size: a sphere light as the disk of its radius through its centre
// facing `point`; a sun as the disk of directions within its angular radius, a disk of radius
// D tan(angle / 2) at distance D along l, D = 1e8 (|point - eye| + 1): its rays' directions differ
// from parallel ones by under 1e-7 of the scene's extent over D. A spot's points count times its
// cone seen from each (the way from the point of the emitter to `point`).
double reference_light_visibility(const SceneShapes& shapes, const Light& light, const SurfacePoint& point,
                                  const glm::dvec3& eye, double offset_scale, int grid = 64);

// sin^2 of the angular radius of a light with a size seen from `position`: a sphere light's facing
// disk, r^2 / (d^2 + r^2); a sun's, tan^2 / (1 + tan^2) of half its angle.
double reference_size_sin_sq(const Light& light, const glm::dvec3& position);

// What a uniform disk of directions of angular radius sigma (sin_sq = sin^2 sigma) lights on a
// surface whose normal makes cosine c with its centre, over what a point light there lights (pi
// sin_sq max(0, c)): max(0, c) where the disk is wholly above or below the horizon, more where it
// straddles it. Integrated numerically over the disk (`steps` rings and sectors, midpoints).
double reference_horizon_cosine(double c, double sin_sq, int steps = 256);

}  // namespace phongcl
