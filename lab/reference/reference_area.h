#pragma once
// Area lights in the reference: both terms integrated over the emitter by Gauss-Legendre product
// rules in double, independent of the kernel's Lambert formula (docs/shading.md "Area lights").
#include <functional>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace phongcl {

struct AreaIntegrals {
  double irradiance = 0.0;  // E: the emitter's visible part, weighted by max(0, n.w)
  double highlight = 0.0;   // S: the same part, weighted by the specular lobe towards w (reference_specular_lobe)
};

// E and S at `position` (unit normal n, unit vector to the eye `eye`, the material's specular model
// and shininess) without the range window, by a
// rule of `order` Gauss points per dimension and per piece: a rect's (s, t) square is cut where the
// horizon crosses its sides and at the foot of the point (the nodes graded towards it, where a
// near point's integrand peaks), a disk's (rho^2, angle) where the horizon crosses its rim; each
// inner range is clipped to the horizon and, for Phong's lobes, to r.w >= 0 (Blinn's have no kink
// above the horizon of a pixel that faces the eye; one that does not is not resolved as well). The
// lobe's peak, where r meets the plane, is graded towards too. 0 behind the emitting side.
AreaIntegrals reference_area_integrals(const AreaLight& light, const glm::dvec3& position, const glm::dvec3& n,
                                       const glm::dvec3& eye, SpecularModel model, double shininess, int order = 48);

// The integral over the emitter's part above the horizon of any coloured lobe towards unit w (dw,
// no n.w added), by the same rules: `sharpness` (a Phong exponent; GGX's is about 2 / alpha^2) grades
// the pieces towards the mirror direction's peak; `reflection_kink` where the lobe is 0 past r.w = 0.
using ColouredLobe = std::function<glm::dvec3(const glm::dvec3& w)>;
glm::dvec3 reference_area_lobe(const AreaLight& light, const glm::dvec3& position, const glm::dvec3& n,
                               const glm::dvec3& eye, const ColouredLobe& lobe, double sharpness, bool reflection_kink,
                               int order = 48);

// The range window of an area light at `position` (1 without a range), as a point light's.
double area_range_window(const AreaLight& light, const glm::dvec3& position);

// The point light at an area light's centre: an area light's hard shadow is that light's shadow
// ray (docs/shadows.md), so a LightReach decides it as it decides a point light's.
Light area_shadow_light(const AreaLight& light);

}  // namespace phongcl
