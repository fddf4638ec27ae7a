/* F = falloff(d) * window(d) * cone(l), and light linking, for the lights that have them (the
 * formula: docs "The shading, exactly"). Each part is compiled in only when the scene uses it
 * (features.h): FALLOFF=k or FALLOFF_MIXED (1/d^k), RANGE_WINDOW (window(d) = clamp(1 - (d/R)^4, 0, 1)^2),
 * SPOT_LIGHTS (cone(l), the smoothstep of the penumbra), SPOT_COSINE_POWER (cone(l) times
 * max(0, c)^p), LIGHT_LINKING=w (w mask words per light).
 * Written for the formula's reader: the factors that are at most 1 multiply first, then 1/d once
 * per power, so the product overflows to +Inf only where 1/d^k itself outgrows them, and a zero
 * factor gives 0, never 0 * Inf = NaN. */
#ifndef PHONGCL_LIGHT_SHAPE_H
#define PHONGCL_LIGHT_SHAPE_H

#include "features.h"
#include "layout.h"
#include "phong_math.h"

/* value * factor for a colour or coefficient factor >= 0, where a weight of +Inf may have reached
 * value: a factor of exactly 0 takes nothing (0, not NaN). A macro, not a function: the product
 * stays inside the caller's expression, so `sum += NONNEGATIVE_TIMES(a, b)` contracts to one fma
 * (OpenCL C's FP_CONTRACT is on) wherever the guard is compiled out. */
#define NONNEGATIVE_TIMES(factor, value) \
  (WEIGHT_CAN_OVERFLOW ? SELECT((factor) > 0, (factor) * (value), 0) : (factor) * (value))

/* 1 where the lane's material is among the light's (its LIGHT_LINKING mask words), else 0.
 * Background lanes (index -1) get bit 31 of the only word with one word, and 0 with more; either
 * way the kernel writes the background colour there. */
realv linked(UNIFORM_SPACE const LinkWord* mask, intv index) {
  intv bits = (intv)0;
  if (LIGHT_LINKING == 1) bits = (intv)(int)mask[0];
  else
    for (int word = 0; word < LIGHT_LINKING; ++word) bits = (index >> 5) == word ? (intv)(int)mask[word] : bits;
  return TO_REALV((bits >> (index & 31)) & 1);
}

/* The linking factor of a light whose mask is `mask`: 0 or 1 per lane; 1 without linking. */
static inline realv link_gate(UNIFORM_SPACE const LinkWord* mask, intv index) {
  return LIGHT_LINKING ? linked(mask, index) : (realv)1;
}

/* 1 - c for c = dot(-l, axis), the cosine of the angle between a spot's axis and the way to the
 * pixel, as |-l - axis|^2 / 2: no cancellation (1 - dot(-l, axis) loses a cone of 1e-3 degrees,
 * 1 - c = 4e-11, entirely: every pixel within 0.03 degrees would be lit). The cone compares it with
 * versines: c >= cos(A/2) is 1 - c <= 1 - cos(A/2), and s = (c - co) / (ci - co) the same ratio. */
realv cone_versine(UNIFORM_SPACE const LightShape* shape, vec3 toward, realv inverse) {
  const vec3 off_axis = make_vec3(fma(-inverse, toward.x, -(realv)shape->axis[0]), fma(-inverse, toward.y, -(realv)shape->axis[1]),
                                  fma(-inverse, toward.z, -(realv)shape->axis[2]));
  return (real)0.5 * dot3(off_axis, off_axis);
}

/* weight / d^powers (0 to PHONGCL_MAX_FALLOFF), one factor 1/d at a time: -cl-fast-relaxed-math
 * would square 1/d first, which overflows float for d < 1e-19 where the products do not. Unrolled by
 * pragma, for speed alone: PoCL's compiler kept falloff 2 as a loop of two passes (docs/kernel.md,
 * "Unrolling" and "Measured"). */
static inline realv times_inverse_powers(realv weight, realv inverse_distance, int powers) {
#pragma clang fp reassociate(off)
#pragma unroll
  for (int power = 0; power < PHONGCL_MAX_FALLOFF; ++power)
    if (power < powers) weight *= inverse_distance;
  return weight;
}

/* `bounded` times cone(l) for toward * inverse = l: the smoothstep of the penumbra, and with
 * SPOT_COSINE_POWER max(0, c)^p (1 for a point light). */
realv times_cone(UNIFORM_SPACE const LightShape* shape, vec3 toward, realv inverse, realv bounded) {
  const realv versine = cone_versine(shape, toward, inverse);
  const realv s = SELECT(versine <= shape->versine_inner, 1,
                         clamp((shape->versine_outer - versine) * shape->inverse_cone_width, (real)0, (real)1));
  bounded *= s * s * (3 - 2 * s);
  /* max(0, c)^p, c = 1 - versine: the power takes its logarithm from the versine near the axis,
   * as the specular lobe's from 1 - v.r, so a large p keeps its precision; p = 0 gives 1. */
  if (SPOT_COSINE_POWER) bounded *= specular_power(1 - versine, versine, (realv)(real)shape->cosine_power);
  return bounded;
}

/* F for one point or spot light; `gate` (0 or 1) is its linking. toward * inverse is l; distance and
 * inverse_distance are d and 1/d, read only with NEEDS_DISTANCE. Without `with_cone` the cone is
 * left out: a soft spot's comes from its emitter's points (soft_shadow.h). */
realv shape_weight(UNIFORM_SPACE const LightShape* shape, vec3 toward, realv inverse, realv distance,
                                 realv inverse_distance, realv gate, int with_cone) {
  realv bounded = gate; /* window * cone * link, in [0, 1] */
  if (RANGE_WINDOW) {
    const realv x = distance * shape->inverse_range, x2 = x * x;
    const realv t = clamp(1 - x2 * x2, (real)0, (real)1);
    bounded *= t * t;
  }
  if (SPOT_LIGHTS && with_cone) bounded = times_cone(shape, toward, inverse, bounded);
  const realv weight = times_inverse_powers(bounded, inverse_distance, FALLOFF_MIXED ? shape->falloff : FALLOFF);
  return WEIGHT_CAN_OVERFLOW ? SELECT(bounded > 0, weight, 0) : weight; /* 0 * (1/d^k = Inf) */
}

/* Whether every lane is clearly beyond a light's range, |d / R|^2 > 1.01, d = |toward| (to the
 * light, or an area light's centre): there the window, and so the light's weight, is exactly 0, so
 * skipping the light changes no bit of the sums. A tile's list holds every light that reaches some
 * pixel of the tile; this drops, per work-item, the ones that reach none of its pixels (area lights,
 * in no list, are all tested). A light without a range (inverse_range 0) is never skipped. toward is
 * scaled by 1 / R before it is squared: d^2 and 1 / R^2 apart overflow float for R = 1e20 and 1e-20
 * (Inf * a tiny factor would skip lights at R / 2). */
bool beyond_range_in_every_lane(vec3 toward, realv inverse_range) {
  const vec3 in_ranges = scale3(toward, inverse_range);
  return all_lanes(LANE_MASK(dot3(in_ranges, in_ranges) > (real)1.01));
}

/* Whether every lane is outside a spot's cone, 1 - c > versine_outer: there the cone factor, and so
 * the weight, is exactly 0 (as beyond the range above). A point light (versine_outer 3) never is. */
bool outside_cone_in_every_lane(UNIFORM_SPACE const LightShape* shape, vec3 toward, realv inverse) {
  return all_lanes(LANE_MASK(cone_versine(shape, toward, inverse) > shape->versine_outer));
}

#endif
