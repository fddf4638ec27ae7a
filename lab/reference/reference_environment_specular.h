#pragma once
// The environment's specular light in the reference, by brute force (docs/environment.md "Specular"):
// the material's own lobe, as a light of that direction gives it (reference_specular_lobe, or the
// Principled BSDF's reference_principled), against every texel of the map with its solid angle,
// unoccluded. Shares nothing with host/environment/prefiltered_map.h or
// kernels/environment_specular.h: no prefiltering, no split sum, no occlusion formula.
#include <glm/glm.hpp>

#include "reference/reference.h"
#include "reference/reference_environment.h"

namespace phongcl {

// The specular term's light at the point seen from direction v (unit, towards the eye): per unit ks
// for the Phong family (their normalisation included), coloured for a Principled point.
glm::dvec3 reference_environment_specular(const EnvironmentLight& light, const ReferenceMap& map, const SurfacePoint& point,
                                          const glm::dvec3& v);

}  // namespace phongcl
