#pragma once
// The environment light in the reference, by brute force (docs/environment.md): every texel of the
// map with its solid angle, cut into cells a fraction of a degree wide where the map is coarse (a
// 1 x 1 map is the whole sphere), summed against the clamped cosine; its visibility from a regular
// grid of cosine-weighted directions, each decided by reference_shadows.h's brute-force ray. Written
// from the specification: it shares nothing with host/environment/ or kernels/environment.h.
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/scene_shapes.h"
#include "reference/reference.h"
#include "scene/scene.h"

namespace phongcl {

// A map as the reference reads it: RGB rows from the top, double.
struct ReferenceMap {
  int width = 0, height = 0;
  std::vector<double> rgb;
};

// The light's map: its file's R, G, B (read again here, through exr/), or its colour as 1 x 1. Files
// are read once per path and modification time.
const ReferenceMap& reference_map(const EnvironmentLight& light);

// strength (1/pi) sum L(w) lobe(w) dw over every texel of the map, each cut into cells under a degree
// (its direction at the cell's centre, with the cell's solid angle), w in the world (or to_world)
// frame: the lookup turned by the light's rotation about +Z as Blender's Mapping node turns it. A
// lobe of 0 skips the texel's read.
glm::dvec3 integrate_environment(const EnvironmentLight& light, const ReferenceMap& map,
                                 const std::function<glm::dvec3(const glm::dvec3&)>& lobe);

// kd = 1's diffuse light from the environment at unit normal n (world or the light's to_world
// frame): strength (1/pi) sum L(w) max(0, n.w) dw over the map's texels, turned by the light's
// rotation about +Z as Blender's Mapping node turns the lookup.
glm::dvec3 reference_environment_light(const EnvironmentLight& light, const ReferenceMap& map, const glm::dvec3& n);

// The same over the directions nothing in `shapes` blocks from the point: every texel's direction
// traced as a directional light's shadow ray (the kernel's offsets, `offset_scale`), so that what the
// scene hides is the map's own light there, the sun's included.
glm::dvec3 reference_environment_visible_light(const EnvironmentLight& light, const ReferenceMap& map,
                                               const SceneShapes& shapes, const SurfacePoint& point, const glm::dvec3& eye,
                                               double offset_scale);

}  // namespace phongcl
