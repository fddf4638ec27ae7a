/* The emitters of lights with a size, as soft shadows sample them (soft_shadow.h; the lab's soft
 * shadow rays, shadow_rays.cl): a flat rect or disk, a sphere light's disk facing the shaded point,
 * a sun's disk of directions, their points for a lattice point (sampling.h), and the diffuse
 * integrand's weight of each. Needs only phong_math.h, so kernels without the shading's flags use it. */
#ifndef PHONGCL_EMITTER_H
#define PHONGCL_EMITTER_H

#include "phong_math.h"

#if PHONGCL_DOUBLE
#define EMITTER_TWO_PI (2 * M_PI)
#else
#define EMITTER_TWO_PI (2 * M_PI_F)
#endif

/* A flat emitter, eye-relative: centre, unit normal of the emitting side, and the axes a rect
 * spans (centre +- u +- v) or a disk's radii along two orthogonal directions. A sun's is the disk
 * of directions about l at unit distance from the point, `center` then l itself. */
typedef struct {
  vec3 center, normal, u, v;
  int disk, directional;
} Emitter;

/* Two unit vectors completing a unit normal to an orthonormal basis, without a branch (Duff et
 * al. 2017, "Building an orthonormal basis, revisited"). */
static inline void orthonormal_basis(vec3 normal, vec3* u, vec3* v) {
  const realv sign = copysign((realv)1, normal.z);
  const realv a = -1 / (sign + normal.z), b = normal.x * normal.y * a;
  *u = make_vec3(1 + sign * normal.x * normal.x * a, sign * b, -sign * normal.x);
  *v = make_vec3(b, sign + normal.y * normal.y * a, -normal.y);
}

/* A disk of radius `radius` about `center` with unit normal `normal`. */
static inline Emitter disk_facing(vec3 center, vec3 normal, real radius, int directional) {
  Emitter emitter;
  emitter.center = center;
  emitter.normal = normal;
  orthonormal_basis(normal, &emitter.u, &emitter.v);
  emitter.u = scale3(emitter.u, radius);
  emitter.v = scale3(emitter.v, radius);
  emitter.disk = 1;
  emitter.directional = directional;
  return emitter;
}

/* A sphere light of radius `radius` at `center` as the disk through its centre facing the point p. */
static inline Emitter sphere_emitter(vec3 center, real radius, vec3 p) {
  return disk_facing(center, unit_or_zero(sub3(p, center)), radius, 0);
}

/* A sun of unit direction l (toward it) whose angular radius has tangent `spread`. */
static inline Emitter sun_emitter(vec3 l, real spread) {
  return disk_facing(l, make_vec3(-l.x, -l.y, -l.z), spread, 1);
}

/* The emitter's point for lattice point (s, t), relative to its centre: a rect's (2s - 1) u +
 * (2t - 1) v; a disk's polar map, radius sqrt(s) and angle 2 pi t (uniform by area). */
static inline vec3 emitter_offset(const Emitter* emitter, realv s, realv t) {
  if (!emitter->disk) return add3(scale3(emitter->u, 2 * s - 1), scale3(emitter->v, 2 * t - 1));
  const realv radius = sqrt(s), angle = (real)EMITTER_TWO_PI * t;
  return add3(scale3(emitter->u, radius * cos(angle)), scale3(emitter->v, radius * sin(angle)));
}

/* The diffuse integrand's weight of a point at d from P (any common scale), capped: a point on the
 * emitter's own plane would weigh +Inf, and Inf / Inf is no fraction. */
static inline realv emitter_weight(vec3 d, vec3 n, vec3 normal) {
  const realv length_sq = dot3(d, d), facing_p = dot3(n, d), facing_light = -dot3(normal, d);
  return SELECT(facing_p > 0 && facing_light > 0, fmin(facing_p * facing_light / (length_sq * length_sq), (real)0x1p64), 0);
}

#endif
