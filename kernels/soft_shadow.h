/* Soft shadows of area lights: the fraction of the emitter a shaded point sees, from `rays` shadow
 * rays (shadow.h) to points spread over it by the shifted R2 lattice (sampling.h). The kernel
 * multiplies the light's exact unshadowed E and S by it: the ratio estimator (Heitz, Hill and McGuire
 * 2018), exact where every ray is free or every ray blocked, noisy only in the penumbra.
 * Each ray counts with the weight the diffuse integrand gives its point, (n.d)(-N.d) / |d|^4 for
 * d = point - P (uniform samples by area), so that the fraction converges to the shadowed E over
 * the unshadowed one; S takes the same fraction (docs/shadows.md "Soft shadows"). A point below P's
 * horizon or behind the emitting side weighs 0 and traces nothing; where every point does, the
 * light keeps its unshadowed value, as the hard shadow keeps lanes whose horizon hides the centre. */
#ifndef PHONGCL_SOFT_SHADOW_H
#define PHONGCL_SOFT_SHADOW_H

#include "area_light.h"
#include "sampling.h"
#include "shadow.h"

/* The emitter's point for lattice point (s, t), relative to its centre: a rect's centre + (2s - 1)
 * u + (2t - 1) v; a disk's polar map, radius sqrt(s) and angle 2 pi t (uniform by area). */
static inline vec3 emitter_offset(UNIFORM_SPACE const AreaLightRecord* light, realv s, realv t) {
  const vec3 u = area_vector(light->axis_u), v = area_vector(light->axis_v);
  if (light->shape == AREA_RECT) return add3(scale3(u, 2 * s - 1), scale3(v, 2 * t - 1));
  const realv radius = sqrt(s), angle = (real)(2 * AREA_PI) * t;
  return add3(scale3(u, radius * cos(angle)), scale3(v, radius * sin(angle)));
}

/* The visible fraction in the lanes of `pending` (1 elsewhere). `caster` is the light's place in
 * the culling's casters, `stream` its own lattice shift's (sampling.h). */
static inline SHADOW_INLINE realv area_light_visibility(const ShadowInputs* shadows, vec3 p, vec3 n,
                                                        UNIFORM_SPACE const AreaLightRecord* light, uint caster,
                                                        uint rays, LatticeShift shift, intv pending) {
  const vec3 center = area_vector(light->center), normal = area_vector(light->normal);
  const vec3 c = sub3(center, p);
  /* The weights in units of |c| + the emitter's extent: they stay inside float for a 1 mm light
   * 1e-3 away as for a 100 m one 1e4 away (a common factor cancels in the fraction). */
  const vec3 u = area_vector(light->axis_u), v = area_vector(light->axis_v);
  const realv inverse_scale = 1 / (sqrt(dot3(c, c)) + sqrt(dot3(u, u) + dot3(v, v)));
  realv seen = 0, total = 0;
  if (!any_lane(pending)) return total + 1;
  for (uint k = 0; k < rays; ++k) {
    realv s, t;
    lattice_point(k, shift, &s, &t);
    const vec3 offset = emitter_offset(light, s, t);
    const vec3 d = scale3(add3(c, offset), inverse_scale);
    const realv length_sq = dot3(d, d), facing_p = dot3(n, d), facing_light = -dot3(normal, d);
    /* capped: a point on the emitter's own plane would weigh +Inf, and Inf / Inf is no fraction */
    const realv weight =
        SELECT(facing_p > 0 && facing_light > 0, fmin(facing_p * facing_light / (length_sq * length_sq), (real)0x1p64), 0);
    const intv blocked = light_blocked(shadows, p, n, add3(center, offset), 0, 0, caster, pending & LANE_MASK(weight > 0));
    total += weight;
    seen += SELECT(TO_REALV(blocked) != 0, 0, weight);
  }
  return SELECT(total > 0, seen / total, 1);
}

#endif
