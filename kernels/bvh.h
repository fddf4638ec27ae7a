/* Shadow rays against the scene's geometry (kernels/shadow_layout.h): whether anything lies between a
 * ray's origin and t_max, for PHONGCL_LANES rays at once (phong_math.h's lanes). With one lane this
 * is the plain single-ray traversal GPUs want; with 16 the rays of a work-item's 16 neighbouring
 * pixels traverse as one packet (Wald et al. 2001): a node is entered when any pending lane's ray
 * meets its box, every box and primitive test runs on all lanes at once, and a lane stops as soon
 * as its ray is blocked (an any-hit query: no nearest hit is sought).
 *
 * Rays are o + t d with 0 < t < t_max, o and d eye-relative like everything the kernels read. A
 * mask is an intv: nonzero where true (-1 in vector lanes, 1 in a scalar). */
#ifndef PHONGCL_BVH_H
#define PHONGCL_BVH_H

#include "shadow_layout.h"
#include "phong_math.h"

typedef struct {
  vec3 origin, direction;
  realv t_max;
} ShadowRay;

static inline int any_lane(intv mask) { return !all_lanes(mask == 0); }

/* A comparison's min and max as selects: one instruction each on SIMD units, where fmin/fmax also
 * handle NaN (none arises: directions are never zero here). */
#define BVH_MIN(a, b) ((a) < (b) ? (a) : (b))
#define BVH_MAX(a, b) ((a) > (b) ? (a) : (b))

/* The far end of a box's t interval is scaled by 1 + 2 gamma(3) for float's unit roundoff (Ize
 * 2013, "Robust BVH ray traversal"): the rounding in (lo - o) / d then never drops a box that the
 * exact ray meets. The boxes themselves are rounded outwards on the host. */
#define BVH_FAR_SCALE 1.0000004f

static inline realv nonzero_component(realv d) { return SELECT(fabs(d) >= 0x1p-80f, d, copysign((realv)0x1p-80f, d)); }

static inline ShadowRay make_shadow_ray(vec3 origin, vec3 direction, realv t_max) {
  ShadowRay ray;
  ray.origin = origin;
  ray.direction = direction;
  ray.t_max = t_max;
  return ray;
}

/* 1 / direction for the slab tests, a zero component replaced by +-2^-80: no 0 * Inf there. Only a
 * traversal needs it (tiled culling's candidates are tested without), so it is made there. */
static inline vec3 inverse_direction(const ShadowRay* ray) {
  return make_vec3(1 / nonzero_component(ray->direction.x), 1 / nonzero_component(ray->direction.y),
                   1 / nonzero_component(ray->direction.z));
}

/* Lanes whose ray meets child c's box (slab test; empty boxes are met by none). */
static inline intv meets_box(__global const BvhNode* node, int c, const ShadowRay* ray, vec3 inverse) {
  const realv x0 = (node->lo_x[c] - ray->origin.x) * inverse.x, x1 = (node->hi_x[c] - ray->origin.x) * inverse.x;
  const realv y0 = (node->lo_y[c] - ray->origin.y) * inverse.y, y1 = (node->hi_y[c] - ray->origin.y) * inverse.y;
  const realv z0 = (node->lo_z[c] - ray->origin.z) * inverse.z, z1 = (node->hi_z[c] - ray->origin.z) * inverse.z;
  const realv t_near = BVH_MAX(BVH_MAX(BVH_MIN(x0, x1), BVH_MIN(y0, y1)), BVH_MAX(BVH_MIN(z0, z1), (realv)0));
  const realv t_far = BVH_MIN(BVH_MIN(BVH_MAX(x0, x1), BVH_MAX(y0, y1)), BVH_MIN(BVH_MAX(z0, z1), ray->t_max));
  return LANE_MASK(t_near <= t_far * BVH_FAR_SCALE);
}

/* The power of two that brings a positive `largest` into [1, 2), from its exponent bits: scaling by
 * it is exact, so it changes no sign, and it keeps a triangle's products finite whatever its size
 * (float: `largest` below 2^127; a subnormal or zero one gets 2^127). Double holds the products of
 * any float coordinates as they are (2^128 cubed is far below 2^1024). */
#if PHONGCL_DOUBLE
#define UNIT_SCALE(largest) ((real)1)
#define UNIT_SCALE_LANES(largest) ((realv)1)
#else
#define UNIT_SCALE(largest) as_float((254 - min(as_int(largest) >> 23, 253)) << 23)
#define UNIT_SCALE_LANES(largest) AS_FLOATV((254 - min(AS_INTV(largest) >> 23, (intv)253)) << 23)
#endif

/* d . (p x q), p and q an edge's corners relative to the ray's origin: which side of the edge the
 * ray's line passes (Plücker's edge function). The triangle across an edge evaluates the same
 * products in the other order (q x p), and without fused multiply-adds that is the exact negation:
 * a ray through a shared edge meets one of its triangles or both, never neither (watertight, as in
 * Woop, Benthin and Wald 2013). */
static inline realv edge_side(vec3 d, vec3 p, vec3 q) {
#pragma clang fp contract(off) reassociate(off)
  return d.x * (p.y * q.z - p.z * q.y) + d.y * (p.z * q.x - p.x * q.z) + d.z * (p.x * q.y - p.y * q.x);
}

/* The ray's line passes through the triangle where its three edge functions agree in sign, the
 * corners taken relative to the origin and scaled by a power of two, so that no product overflows
 * whatever the triangle's size. The ray crosses the triangle's plane x.f = f.f at
 * t = (f.f - f.o) / f.d, f the plane's point nearest the eye, which the host works out in double
 * (shadow_layout.h): from the float corners, a plane's place near the eye sums products of the
 * triangle's size, and a tilted quad 2e8 across would move by units. Both faces block light; a
 * degenerate triangle (f = 0) blocks nothing. */
static inline intv meets_large_triangle(__global const ShadowPrimitive* triangle, const ShadowRay* ray) {
#pragma clang fp contract(off) reassociate(off)
  const vec3 o = ray->origin, d = ray->direction;
  const real ax = triangle->row[0][0], ay = triangle->row[0][1], az = triangle->row[0][2];
  const real bx = triangle->row[1][0], by = triangle->row[1][1], bz = triangle->row[1][2];
  const real cx = triangle->row[2][0], cy = triangle->row[2][1], cz = triangle->row[2][2];
  const real largest = fmax(fmax(fmax(fabs(ax), fabs(ay)), fmax(fabs(az), fabs(bx))),
                            fmax(fmax(fabs(by), fabs(bz)), fmax(fabs(cx), fmax(fabs(cy), fabs(cz)))));
  /* |corner - o| < 2 max(|corner|, |o|), so below 4 once scaled. */
  const realv scale = UNIT_SCALE_LANES(fmax((realv)largest, largest_magnitude(o)));
  const vec3 a = make_vec3((ax - o.x) * scale, (ay - o.y) * scale, (az - o.z) * scale);
  const vec3 b = make_vec3((bx - o.x) * scale, (by - o.y) * scale, (bz - o.z) * scale);
  const vec3 c = make_vec3((cx - o.x) * scale, (cy - o.y) * scale, (cz - o.z) * scale);
  const realv u = edge_side(d, b, c), v = edge_side(d, c, a), w = edge_side(d, a, b);
  const intv inside = LANE_MASK((u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0));
  const real fx = triangle->row[0][3], fy = triangle->row[1][3], fz = triangle->row[2][3];
  /* The plane's equation scaled by a power of two: f.f would overflow from |f| = 2^64. */
  const real unit = UNIT_SCALE(fmax(fabs(fx), fmax(fabs(fy), fabs(fz))));
  const real nx = fx * unit, ny = fy * unit, nz = fz * unit;
  const realv to_plane = (nx * fx + ny * fy + nz * fz) - (nx * o.x + ny * o.y + nz * o.z);
  const realv approach = nx * d.x + ny * d.y + nz * d.z;
  const realv ahead = to_plane * SELECT(approach < 0, -1, 1);
  return inside & LANE_MASK(ahead > 0 && ahead < ray->t_max * fabs(approach));
}

/* Moller-Trumbore without a division: u, v and t are compared against det scaled, sign folded in.
 * Both faces block light. A degenerate triangle (det = 0) blocks nothing. Its products of the
 * triangle's size lose the plane's place near the eye for triangles much larger than the scene
 * around the eye: the host marks only those within PHONGCL_SMALL_TRIANGLE_REACH for it. */
static inline intv meets_small_triangle(__global const ShadowPrimitive* triangle, const ShadowRay* ray) {
  const real v0x = triangle->row[0][0], v0y = triangle->row[0][1], v0z = triangle->row[0][2];
  const real e1x = triangle->row[1][0] - v0x, e1y = triangle->row[1][1] - v0y, e1z = triangle->row[1][2] - v0z;
  const real e2x = triangle->row[2][0] - v0x, e2y = triangle->row[2][1] - v0y, e2z = triangle->row[2][2] - v0z;
  const vec3 d = ray->direction;
  const realv px = d.y * e2z - d.z * e2y, py = d.z * e2x - d.x * e2z, pz = d.x * e2y - d.y * e2x;
  const realv det = e1x * px + e1y * py + e1z * pz;
  const realv sx = ray->origin.x - v0x, sy = ray->origin.y - v0y, sz = ray->origin.z - v0z;
  const realv qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
  const realv flip = SELECT(det < 0, -1, 1);
  const realv u = (sx * px + sy * py + sz * pz) * flip;
  const realv v = (d.x * qx + d.y * qy + d.z * qz) * flip;
  const realv t = (e2x * qx + e2y * qy + e2z * qz) * flip;
  const realv size = fabs(det);
  return LANE_MASK(size > 0 && u >= 0 && v >= 0 && u + v <= size && t > 0 && t < ray->t_max * size);
}

/* Which test a triangle takes is the host's (shadow_layout.h): the same for every lane. */
static inline intv meets_triangle(__global const ShadowPrimitive* triangle, const ShadowRay* ray) {
  if (as_uint(triangle->row[0][3]) == PHONGCL_SMALL_TRIANGLE) return meets_small_triangle(triangle, ray);
  return meets_large_triangle(triangle, ray);
}

/* The unit sphere in u = A x + b: f(t) = |u(o) + t A d|^2 - 1 = a t^2 + 2 b' t + c, with
 * a = |A d|^2, b' = u(o).A d, c = |u(o)|^2 - 1; the ray is blocked where its segment crosses the
 * surface (a segment wholly inside, a light and a point both within a sphere, is not): where one
 * end is inside (f < 0) and the other not, or both are outside and f's minimum, at t = -b'/a, lies
 * between them and reaches the surface (b'^2 >= a c). The same roots as -b' -+ sqrt(b'^2 - a c)
 * in (0, t_max), without the square root, whose latency the test waited on. */
static inline intv meets_sphere(__global const ShadowPrimitive* sphere, const ShadowRay* ray) {
  const vec3 o = ray->origin, d = ray->direction;
  vec3 uo, ud;
  uo.x = sphere->row[0][0] * o.x + sphere->row[0][1] * o.y + sphere->row[0][2] * o.z + sphere->row[0][3];
  uo.y = sphere->row[1][0] * o.x + sphere->row[1][1] * o.y + sphere->row[1][2] * o.z + sphere->row[1][3];
  uo.z = sphere->row[2][0] * o.x + sphere->row[2][1] * o.y + sphere->row[2][2] * o.z + sphere->row[2][3];
  ud.x = sphere->row[0][0] * d.x + sphere->row[0][1] * d.y + sphere->row[0][2] * d.z;
  ud.y = sphere->row[1][0] * d.x + sphere->row[1][1] * d.y + sphere->row[1][2] * d.z;
  ud.z = sphere->row[2][0] * d.x + sphere->row[2][1] * d.y + sphere->row[2][2] * d.z;
  const realv a = dot3(ud, ud), half_b = dot3(uo, ud), c = dot3(uo, uo) - 1;
  const realv t_max = ray->t_max, at_end = fma(t_max, fma(a, t_max, 2 * half_b), c);
  const intv starts_inside = LANE_MASK(c < 0), ends_inside = LANE_MASK(at_end < 0);
  const intv dips = LANE_MASK(half_b < 0 && -half_b < t_max * a && half_b * half_b >= a * c);
  return (starts_inside ^ ends_inside) | (~(starts_inside | ends_inside) & dips);
}

/* Unbounded planes are tested by every ray: t = (offset - n.o) / n.d in (0, t_max). */
static inline intv meets_plane(__global const ShadowPlane* plane, const ShadowRay* ray) {
  const realv to_plane = plane->offset - (plane->normal[0] * ray->origin.x + plane->normal[1] * ray->origin.y +
                                          plane->normal[2] * ray->origin.z);
  const realv approach = plane->normal[0] * ray->direction.x + plane->normal[1] * ray->direction.y +
                         plane->normal[2] * ray->direction.z;
  return LANE_MASK(to_plane * approach > 0 && fabs(to_plane) < ray->t_max * fabs(approach));
}

/* The lanes of `pending` blocked by a run of primitives (a leaf) or of planes. */
static inline intv run_blocks(__global const ShadowPrimitive* primitives, __global const ShadowPlane* planes,
                              uint first, uint kind_count, const ShadowRay* ray, intv pending) {
  intv blocked = pending & 0;
  const uint count = kind_count >> PHONGCL_BVH_KIND_BITS;
  const uint kind = kind_count & PHONGCL_BVH_KIND_MASK;
  for (uint k = first; k < first + count; ++k)
    blocked |= kind == BVH_TRIANGLES ? meets_triangle(&primitives[k], ray)
               : kind == BVH_SPHERES ? meets_sphere(&primitives[k], ray)
                                     : meets_plane(&planes[k], ray);
  return blocked & pending;
}

/* A walk down the BVH: the node being visited and the ones left for later (one per level at most). */
typedef struct {
  uint stack[PHONGCL_BVH_MAX_DEPTH];
  int size;
  uint node;
} BvhWalk;

/* The walk's next node once a node's children are tested: the first to enter, the second kept on
 * the stack when both are, else the stack's top; false when the walk is over. */
static inline bool next_node(BvhWalk* walk, __global const BvhNode* record, const int enter[2]) {
  if (enter[0] && enter[1]) walk->stack[walk->size++] = record->first[1];
  if (enter[0] || enter[1]) {
    walk->node = record->first[enter[0] ? 0 : 1];
    return true;
  }
  if (walk->size == 0) return false;
  walk->node = walk->stack[--walk->size];
  return true;
}

/* The lanes of `pending` whose ray is blocked by a plane or by a primitive under the BVH. */
static inline intv shadow_ray_blocked(__global const BvhNode* nodes, uint node_count,
                                      __global const ShadowPrimitive* primitives,
                                      __global const ShadowPlane* planes, uint plane_count, const ShadowRay* ray,
                                      intv pending) {
  intv blocked = pending & 0;
  for (uint k = 0; k < plane_count; ++k) blocked |= meets_plane(&planes[k], ray) & pending;
  pending &= ~blocked;
  if (node_count == 0 || !any_lane(pending)) return blocked;
  const vec3 inverse = inverse_direction(ray);
  BvhWalk walk = {.size = 0, .node = 0};
  for (;;) {
    __global const BvhNode* record = &nodes[walk.node];
    int enter[2];
    for (int c = 0; c < 2; ++c) {
      enter[c] = any_lane(meets_box(record, c, ray, inverse) & pending);
      const uint kind_count = record->kind_count[c];
      if (enter[c] && (kind_count & PHONGCL_BVH_KIND_MASK) != BVH_INNER) {
        const intv hit = run_blocks(primitives, planes, record->first[c], kind_count, ray, pending);
        blocked |= hit;
        pending &= ~hit;
        if (!any_lane(pending)) return blocked;
        enter[c] = 0;
      }
    }
    if (!next_node(&walk, record, enter)) return blocked;
  }
}

/* The lanes of `pending` blocked by a tile's candidates for one light (kernels/shadow_cull.cl). */
static inline intv candidates_block(__global const ShadowCandidate* candidates, uint count,
                                    __global const ShadowPrimitive* primitives, __global const ShadowPlane* planes,
                                    const ShadowRay* ray, intv pending) {
  intv blocked = pending & 0;
  for (uint j = 0; j < count && any_lane(pending); ++j) {
    const intv hit = run_blocks(primitives, planes, candidates[j].first, candidates[j].kind_count, ray, pending);
    blocked |= hit;
    pending &= ~hit;
  }
  return blocked;
}

#endif
