/* Shadows: the ray from a shaded point toward a light, for the geometry's BVH (bvh.h).
 *
 * Self-intersection: a G-buffer's position is a float rounding of the renderer's surface point,
 * off the surface by a few ulp of its coordinates (the world's, which the renderer stored, and the
 * eye-relative ones the kernel reads). The ray starts eps(P) along the unit normal, on the side
 * the light is (only lights with n.l > 0 are traced), and stops eps(L) short of a point or spot
 * light, with
 *     eps(X) = offset_scale * (|X - eye|_inf + |eye|_inf)
 * (|X - eye| + |eye| bounds X's world coordinates), offset_scale PHONGCL_SHADOW_OFFSET_FLOAT or _HALF
 * (bvh_layout.h) as the positions were stored. A directional
 * light's ray runs to t = 2^100 along the unit l. */
#ifndef PHONGCL_SHADOW_H
#define PHONGCL_SHADOW_H

#include "bvh.h"

/* The far end of a directional light's ray: beyond any float scene, and t_max * |n.d| stays finite. */
#define SHADOW_DIRECTIONAL_T_MAX 0x1p100f

/* p: the shaded point and n its unit normal (eye-relative); toward: the light's position minus p,
 * with inverse = 1 / |toward|; eye_extent = |eye|_inf. */
static inline ShadowRay shadow_ray_to_point(vec3 p, vec3 n, vec3 toward, realv inverse, real offset_scale,
                                            real eye_extent) {
  const realv leave = offset_scale * (largest_magnitude(p) + eye_extent);
  const vec3 light = make_vec3(p.x + toward.x, p.y + toward.y, p.z + toward.z);
  const realv stop = offset_scale * (largest_magnitude(light) + eye_extent);
  const vec3 origin = make_vec3(fma(leave, n.x, p.x), fma(leave, n.y, p.y), fma(leave, n.z, p.z));
  return make_shadow_ray(origin, sub3(light, origin), 1 - stop * inverse);
}

/* l: the unit vector toward a directional light. */
static inline ShadowRay shadow_ray_to_direction(vec3 p, vec3 n, vec3 l, real offset_scale, real eye_extent) {
  const realv leave = offset_scale * (largest_magnitude(p) + eye_extent);
  const vec3 origin = make_vec3(fma(leave, n.x, p.x), fma(leave, n.y, p.y), fma(leave, n.z, p.z));
  return make_shadow_ray(origin, l, (realv)SHADOW_DIRECTIONAL_T_MAX);
}

#endif
