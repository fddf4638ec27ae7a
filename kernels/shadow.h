/* Shadows: the ray from a shaded point toward a light, traced against the geometry's BVH (bvh.h)
 * or marched across the frame's depth plane (screen space, below).
 *
 * Self-intersection: a G-buffer's position is a float rounding of the renderer's surface point,
 * off the surface by a few ulp of its coordinates (the world's, which the renderer stored, and the
 * eye-relative ones the kernel reads). The ray starts eps(P) along the unit normal, on the side
 * the light is (only lights with n.l > 0 are traced), and stops eps(L) short of a point or spot
 * light, with
 *     eps(X) = offset_scale * (|X - eye|_inf + |eye|_inf)
 * (|X - eye| + |eye| bounds X's world coordinates), offset_scale PHONGCL_SHADOW_OFFSET_FLOAT or _HALF
 * (shadow_layout.h) as the positions were stored. A directional
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

/* A shaded point's shadow ray toward a light: a point or spot light at eye-relative `where`, or a
 * directional light whose unit l (toward it) is `where`. `traced` loses the lanes facing away from
 * the light (n.l <= 0: the light adds nothing there, so nothing is traced). */
static inline ShadowRay shadow_ray_toward(vec3 p, vec3 n, vec3 where, int directional, real offset_scale,
                                          real eye_extent, intv* traced) {
  if (directional) {
    *traced &= LANE_MASK(dot3(n, where) > 0);
    return shadow_ray_to_direction(p, n, where, offset_scale, eye_extent);
  }
  const vec3 toward = sub3(where, p);
  vec3 scaled = toward; /* distance_in_range() may rescale it, keeping its direction */
  realv distance, inverse_distance;
  distance_in_range(&scaled, &distance, &inverse_distance);
  *traced &= LANE_MASK(dot3(n, scaled) > 0);
  return shadow_ray_to_point(p, n, toward, inverse_distance, offset_scale, eye_extent);
}

/* Screen space: the ray is sampled at `steps` points evenly spaced in the image between where it
 * starts and where it leaves the image, the depth range of the frame's surfaces or ends (at the
 * light); a sample lies in the shadow of the surface seen at its pixel when it is behind that
 * surface by more than a bias (the surface's own depth times 2^-9: a ray leaving a surface at a
 * grazing angle stays in front of its neighbours' pixel-centre depths) and by less than the
 * thickness. Depth is interpolated as 1/z, which is linear in the image. What the camera cannot
 * see cannot shadow: occluders outside the frame or hidden behind what the camera sees are missed,
 * and a surface is taken to be `thickness` deep. */
#define SCREEN_MARCH_BIAS 0x1p-9f

/* The part of the ray the march covers, as t in [t_begin, t_end]: in front of the camera between
 * the frame's depths, and inside the image. Each bound is linear in t once multiplied by the
 * (positive) depth: u(t) = scale (a + t b) / (z0 + t dz) + centre >= 0 <=> (centre z0 + scale a) +
 * t (centre dz + scale b) >= 0. Empty when t_begin > t_end. */
static inline void clip_to_image(const ShadowRay* ray, ScreenMarch march, realv* t_begin, realv* t_end) {
  const vec3 o = ray->origin, d = ray->direction;
  const vec3 forward = make_vec3(march.forward[0], march.forward[1], march.forward[2]);
  const vec3 right = make_vec3(march.right[0], march.right[1], march.right[2]);
  const vec3 up = make_vec3(march.up[0], march.up[1], march.up[2]);
  const realv z0 = dot3(o, forward), dz = dot3(d, forward);
  /* Each constraint c0 + t c1 >= 0. */
  realv c0[6], c1[6];
  c0[0] = z0 - march.near_depth, c1[0] = dz;
  c0[1] = march.far_depth - z0, c1[1] = -dz;
  const realv x0 = dot3(o, right), dx = dot3(d, right), y0 = dot3(o, up), dy = dot3(d, up);
  c0[2] = march.centre_x * z0 + march.scale_x * x0, c1[2] = march.centre_x * dz + march.scale_x * dx;
  c0[3] = (march.width - march.centre_x) * z0 - march.scale_x * x0, c1[3] = (march.width - march.centre_x) * dz - march.scale_x * dx;
  c0[4] = march.centre_y * z0 - march.scale_y * y0, c1[4] = march.centre_y * dz - march.scale_y * dy;
  c0[5] = (march.height - march.centre_y) * z0 + march.scale_y * y0, c1[5] = (march.height - march.centre_y) * dz + march.scale_y * dy;
  realv begin = 0, end = BVH_MIN(ray->t_max, (realv)SHADOW_DIRECTIONAL_T_MAX);
  for (int k = 0; k < 6; ++k) {
    const realv bound = -c0[k] / c1[k];
    begin = SELECT(c1[k] > 0, BVH_MAX(begin, bound), begin);
    end = SELECT(c1[k] < 0, BVH_MIN(end, bound), end);
    end = SELECT(c1[k] == 0 && c0[k] < 0, -1, end); /* parallel and outside */
  }
  *t_begin = begin;
  *t_end = end;
}

/* The depth plane at each lane's pixel (x, y), clamped into the plane: a gather, lane by lane
 * (OpenCL C has no vector gather). */
static inline realv depth_at(__global const float* depth, ScreenMarch march, realv x, realv y) {
#if PHONGCL_LANES == 1
  const int column = clamp((int)x, 0, (int)march.width - 1), row = clamp((int)y, 0, (int)march.height - 1);
  return depth[(size_t)row * march.width + column];
#else
  const intv column = clamp(PHONGCL_XCAT(convert_int, PHONGCL_LANES)(x), (intv)0, (intv)(march.width - 1));
  const intv row = clamp(PHONGCL_XCAT(convert_int, PHONGCL_LANES)(y), (intv)0, (intv)(march.height - 1));
  const intv index = row * (int)march.width + column;
  int lanes[PHONGCL_LANES];
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(index, 0, lanes);
  real values[PHONGCL_LANES];
  for (int k = 0; k < PHONGCL_LANES; ++k) values[k] = depth[lanes[k]];
  return PHONGCL_XCAT(vload, PHONGCL_LANES)(0, values);
#endif
}

/* The lanes of `pending` whose march meets a surface of the depth plane. */
static inline intv screen_march_blocked(__global const float* depth, ScreenMarch march, const ShadowRay* ray,
                                        intv pending) {
  intv blocked = pending & 0;
  realv t_begin, t_end;
  clip_to_image(ray, march, &t_begin, &t_end);
  pending &= LANE_MASK(t_begin < t_end);
  if (!any_lane(pending)) return blocked;
  const vec3 forward = make_vec3(march.forward[0], march.forward[1], march.forward[2]);
  const vec3 right = make_vec3(march.right[0], march.right[1], march.right[2]);
  const vec3 up = make_vec3(march.up[0], march.up[1], march.up[2]);
  /* The clipped segment's ends in the image: pixel coordinates and 1 / depth. */
  const vec3 a = make_vec3(fma(t_begin, ray->direction.x, ray->origin.x), fma(t_begin, ray->direction.y, ray->origin.y),
                           fma(t_begin, ray->direction.z, ray->origin.z));
  const vec3 b = make_vec3(fma(t_end, ray->direction.x, ray->origin.x), fma(t_end, ray->direction.y, ray->origin.y),
                           fma(t_end, ray->direction.z, ray->origin.z));
  const realv inverse_a = 1 / dot3(a, forward), inverse_b = 1 / dot3(b, forward);
  const realv ax = march.centre_x + march.scale_x * dot3(a, right) * inverse_a;
  const realv ay = march.centre_y - march.scale_y * dot3(a, up) * inverse_a;
  const realv bx = march.centre_x + march.scale_x * dot3(b, right) * inverse_b;
  const realv by = march.centre_y - march.scale_y * dot3(b, up) * inverse_b;
  /* The first sample a pixel away from the start, the last at the end. */
  const realv pixels = sqrt((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
  const realv first = BVH_MIN((realv)1, 1 / BVH_MAX(pixels, (realv)1));
  const realv step = (1 - first) / (realv)BVH_MAX(march.steps - 1, 1u);
  const realv depth_step = fabs(1 / inverse_b - 1 / inverse_a) / (realv)march.steps;
  const realv thickness = march.thickness > 0 ? (realv)march.thickness : 2 * depth_step;
  const realv relative = march.thickness < 0 ? (realv)-march.thickness : 0;
  for (uint k = 0; k < march.steps && any_lane(pending); ++k) {
    const realv s = first + step * (realv)k;
    const realv ray_depth = 1 / fma(s, inverse_b - inverse_a, inverse_a);
    const realv surface = depth_at(depth, march, fma(s, bx - ax, ax), fma(s, by - ay, ay));
    const realv deep = march.thickness < 0 ? relative * surface : thickness;
    const intv hit = pending & LANE_MASK(ray_depth > surface * (1 + SCREEN_MARCH_BIAS) && ray_depth < surface + deep);
    blocked |= hit;
    pending &= ~hit;
  }
  return blocked;
}

/* What the shading kernel's shadow tests read (phong.cl): the geometry (shadow_layout.h), the screen
 * march's depth plane, the frame's shadow scalars, and with tiled shadow culling (tiles > 0) the
 * lists of shadow_cull.cl for the work-item's tile: pair caster * tiles + tile holds counts[pair]
 * candidates from candidates[offsets[pair]], or PHONGCL_SHADOW_TRAVERSE. */
typedef struct {
  __global const BvhNode* nodes;
  __global const ShadowPrimitive* primitives;
  __global const ShadowPlane* planes;
  __global const float* depth;
  ShadowFrame frame;
  __global const uint* counts;
  __global const uint* offsets;
  __global const ShadowCandidate* candidates;
  uint tiles, tile;
} ShadowInputs;

/* Inlined into each light's code whatever its size: called, it takes the shaded point and the light
 * as vec3s on the stack and spills the light loop's sums around the call (docs/kernel.md, "Measured"). */
#define SHADOW_INLINE __attribute__((always_inline))

/* The lanes of `pending` that a light does not reach (shadow_ray_toward's light): its ray is blocked
 * by the geometry, or with `screen` by a surface of the depth plane. `caster` is the light's place
 * in the culling's list of shadow-casting lights: where its tile's list is empty nothing can block
 * the tile's rays, and no ray is made. */
static inline SHADOW_INLINE intv light_blocked(const ShadowInputs* shadows, vec3 p, vec3 n, vec3 where, int directional, int screen,
                                 uint caster, intv pending) {
  if (!any_lane(pending)) return pending;
  uint pair = 0, count = PHONGCL_SHADOW_TRAVERSE;
  if (!screen && shadows->tile < shadows->tiles) {
    pair = caster * shadows->tiles + shadows->tile;
    count = shadows->counts[pair];
    if (count == 0) return pending & 0;
  }
  const ShadowRay ray = shadow_ray_toward(p, n, where, directional, shadows->frame.offset_scale,
                                          shadows->frame.eye_extent, &pending);
  pending &= LANE_MASK(ray.t_max > 0);
  if (!any_lane(pending)) return pending;
  if (screen) return screen_march_blocked(shadows->depth, shadows->frame.march, &ray, pending);
  if (count != PHONGCL_SHADOW_TRAVERSE)
    return candidates_block(&shadows->candidates[shadows->offsets[pair]], count, shadows->primitives, shadows->planes,
                            &ray, pending);
  return shadow_ray_blocked(shadows->nodes, shadows->frame.node_count, shadows->primitives, shadows->planes,
                            shadows->frame.plane_count, &ray, pending);
}

#endif
