/* Soft shadows of lights with a size: the fraction of the emitter a shaded point sees, from `rays`
 * shadow rays (shadow.h) to points spread over it by the shifted R2 lattice (sampling.h). The kernel
 * multiplies the light's unshadowed light by it: the ratio estimator (Heitz, Hill and McGuire 2018),
 * exact where every ray is free or every ray blocked, noisy only in the penumbra.
 * The emitter is an area light's rect or disk, a sphere light's disk facing the point (what the
 * point sees of a sphere of radius r is a disk of radius r, nearly, for r well below the distance),
 * or a sun's disk of directions about l. Each ray counts with the weight the diffuse integrand gives
 * its point, (n.d)(-N.d) / |d|^4 for d = point - P (uniform samples by area), so that the fraction
 * converges to the shadowed E over the unshadowed one; S takes the same fraction (docs/shadows.md
 * "Soft shadows"). A point below P's horizon or behind the emitting side weighs 0 and traces
 * nothing; where every point does, the light keeps its unshadowed value, as the hard shadow keeps
 * lanes whose horizon hides the centre. */
#ifndef PHONGCL_SOFT_SHADOW_H
#define PHONGCL_SOFT_SHADOW_H

#include "area_light.h"
#include "emitter.h"
#include "light_shape.h"
#include "sampling.h"
#include "shadow.h"

/* Adaptive: a light of more rays traces this many first (a stratified prefix of the lattice), and a
 * lane whose traced rays all agree stops there: where they are all blocked its fraction is 0 and
 * where all free 1, as the full count would give but for an occluder smaller than the prefix's
 * spacing. Only lanes in a penumbra trace the rest: a penumbra's noise at the full count, a lit or
 * hidden pixel's cost at this one (docs/shadows.md "Soft shadows": 16, measured against Cycles). */
#define SHADOW_PROBE_RAYS 16u

/* Where a spot's cone changes across its emitter (its blend or edge meets the emitter), its mean is
 * taken from at least this many points of the lattice, with no ray: the rays then weigh the shadow
 * alone, so a lit pixel at the cone's blurred edge has the quadrature's error, not the rays' noise
 * (docs/shadows.md "Soft shadows": 256, measured against Cycles and timed). */
#define SPOT_CONE_POINTS 256u

static inline Emitter area_emitter(UNIFORM_SPACE const AreaLightRecord* light) {
  const Emitter emitter = {area_vector(light->center), area_vector(light->normal), area_vector(light->axis_u),
                           area_vector(light->axis_v), light->shape == AREA_DISK, 0};
  return emitter;
}

/* The weights in units of |c| + the emitter's extent, c its centre from P: they stay inside float
 * for a 1 mm light 1e-3 away as for a 100 m one 1e4 away (a common factor cancels in a fraction). */
static inline realv emitter_inverse_scale(const Emitter* emitter, vec3 c) {
  return 1 / (sqrt(dot3(c, c)) + sqrt(dot3(emitter->u, emitter->u) + dot3(emitter->v, emitter->v)));
}

/* `weight` times a spot's cone seen the way from the point at d (from P) to P; the floor keeps a
 * point at P from dividing by 0. */
static inline realv times_cone_from(UNIFORM_SPACE const LightShape* cone, vec3 d, realv weight) {
  return times_cone(cone, d, 1 / sqrt(fmax(dot3(d, d), (real)1e-30)), weight);
}

/* The mean of a spot's cone over its emitter, each point seen the way from it to P and weighted by
 * the diffuse integrand, from `points` points of the lattice (no rays); where no point faces P, the
 * cone seen from the centre. */
static inline realv emitter_cone_mean(const Emitter* emitter, vec3 c, vec3 n, UNIFORM_SPACE const LightShape* cone,
                                      uint points, LatticeShift shift) {
  const realv inverse_scale = emitter_inverse_scale(emitter, c);
  realv in_cone = 0, total = 0;
  for (uint k = 0; k < points; ++k) {
    realv s, t;
    lattice_point(k, shift, &s, &t);
    const vec3 d = add3(c, emitter_offset(emitter, s, t));
    const realv weight = emitter_weight(scale3(d, inverse_scale), n, emitter->normal);
    total += weight;
    in_cone += times_cone_from(cone, d, weight);
  }
  return SELECT(total > 0, in_cone / total, times_cone_from(cone, c, 1));
}

/* Whether a spot's cone changes across a sphere light's disk facing P, c its centre from P: the
 * directions from its points to P lie within sigma of the centre's (tan sigma = r / |c|, widened
 * by 1% for rounding), and the cone changes only between its inner and outer versines. */
static inline intv cone_changes_across(const Emitter* emitter, vec3 c, UNIFORM_SPACE const LightShape* cone) {
  const realv inverse = 1 / sqrt(fmax(dot3(c, c), (real)1e-30));
  const realv versine = cone_versine(cone, c, inverse);
  const realv cosine = 1 - versine, sine = sqrt(fmax(versine * (2 - versine), (real)0));
  const realv tangent = (real)1.01 * sqrt(dot3(emitter->u, emitter->u)) * inverse;
  const realv cos_sigma = 1 / sqrt(1 + tangent * tangent), sin_sigma = tangent * cos_sigma;
  /* 1 - cos(angle + sigma) and 1 - cos(angle - sigma), the versines of the farthest and nearest ways */
  const realv farthest = 1 - cosine * cos_sigma + sine * sin_sigma, nearest = 1 - cosine * cos_sigma - sine * sin_sigma;
  return LANE_MASK(farthest > cone->versine_inner) & LANE_MASK(nearest < cone->versine_outer);
}

/* The visible fraction of an emitter in the lanes of `pending` (1 elsewhere). `caster` is the
 * light's place in the culling's casters, `shift` its lattice's (sampling.h). A sun's rays run to
 * infinity along the directions through its disk and traverse the BVH: tiled shadow culling's hulls
 * are swept along l alone. With `cone` (a spot's shape; 0 for none) the fraction is the cone's mean
 * over the emitter, as Cycles evaluates a spot of some radius (each point's cone the way from it to
 * P, its edge blurred by the emitter), times the visible share of the emitter weighted by that
 * cone (a ray to a point outside the cone weighs 0 and is not traced); the mean is the rays' own
 * where the cone does not change across the emitter, a denser quadrature's where it does. */
static inline SHADOW_INLINE realv emitter_visibility(const ShadowInputs* shadows, vec3 p, vec3 n, const Emitter* emitter,
                                                     UNIFORM_SPACE const LightShape* cone, uint caster, uint rays,
                                                     LatticeShift shift, intv pending) {
  ShadowInputs traced = *shadows;
  if (emitter->directional) traced.tiles = 0;
  const vec3 c = emitter->directional ? emitter->center : sub3(emitter->center, p);
  const realv inverse_scale = emitter_inverse_scale(emitter, c);
  realv seen = 0, total = 0, facing_total = 0, traced_rays = 0, blocked_rays = 0;
  for (uint k = 0; k < rays; ++k) {
    if (k == SHADOW_PROBE_RAYS)
      pending &= ~(LANE_MASK(traced_rays > 0) & (LANE_MASK(blocked_rays == traced_rays) | LANE_MASK(blocked_rays == 0)));
    if (!any_lane(pending)) break;
    realv s, t;
    lattice_point(k, shift, &s, &t);
    const vec3 offset = emitter_offset(emitter, s, t);
    const vec3 d = add3(c, offset);
    const realv facing = emitter_weight(scale3(d, inverse_scale), n, emitter->normal);
    const realv weight = SELECT(TO_REALV(pending) != 0, cone ? times_cone_from(cone, d, facing) : facing, 0);
    const vec3 where = emitter->directional ? unit_or_zero(d) : add3(emitter->center, offset);
    const intv blocked =
        light_blocked(&traced, p, n, where, emitter->directional, SCREEN_SHADOWS, caster, pending & LANE_MASK(weight > 0));
    total += weight;
    if (cone) facing_total += SELECT(TO_REALV(pending) != 0, facing, 0);
    traced_rays += SELECT(weight > 0, 1, 0);
    blocked_rays += SELECT(TO_REALV(blocked) != 0, 1, 0);
    seen += SELECT(TO_REALV(blocked) != 0, 0, weight);
  }
  const realv visible = SELECT(total > 0, seen / total, 1);
  if (!cone) return visible;
  const intv changes = cone_changes_across(emitter, c, cone);
  realv mean = SELECT(facing_total > 0, total / facing_total, times_cone_from(cone, c, 1));
  if (any_lane(changes))
    mean = SELECT(TO_REALV(changes) != 0, emitter_cone_mean(emitter, c, n, cone, max(rays, SPOT_CONE_POINTS), shift), mean);
  return mean * visible;
}

/* What a light of angular radius sigma lights, relative to a point light's at its centre, for
 * c = n.l and sin_sq = sin(sigma)^2: E / (pi sin_sq), the irradiance E of a uniform disk of
 * directions (a sphere's or a sun's) over the surface's horizon, which is max(0, c) wherever the
 * whole disk is above the horizon or below it (c^2 >= sin_sq) and, where it straddles it, the
 * closed form of the part above (a uniform spherical cap cut by a plane; as Frostbite's sphere
 * lights, Lagarde and de Rousiers 2014): positive a little past c = 0, as Cycles lights there. */
static inline realv horizon_cosine(realv c, realv sin_sq) {
  const realv sine = sqrt(fmax(1 - c * c, (real)0));
  const realv cotangent = sqrt(1 / sin_sq - 1);
  const realv y = clamp(-cotangent * c / fmax(sine, (real)1e-12), (real)-1, (real)1);
  const realv t = sine * sqrt(fmax(1 - y * y, (real)0));
  const realv straddling = ((c * acos(y) - cotangent * t) * sin_sq + atan(t / cotangent)) / ((real)AREA_PI * sin_sq);
  return SELECT(c * c >= sin_sq, fmax(c, (real)0), fmax(straddling, (real)0));
}

#endif
