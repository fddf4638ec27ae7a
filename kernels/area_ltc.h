/* Cycles' Principled (v1) GGX highlight under a rect or disk area light, by linearly transformed
 * cosines (Heitz, Dupuy, Hill and Neubelt 2016). In the frame x towards v, z = n, the lobe pi f n.l
 * (Fresnel apart) is fitted as magnitude * D(M^-1 w / |M^-1 w|) |det M^-1| / |M^-1 w|^3 with D the
 * clamped cosine over pi: its integral over the emitter's part above the horizon is magnitude times
 * the clamped cosine's over that polygon transformed by M^-1 and clipped to z >= 0, Lambert's closed
 * form (as area_light.h's, here as a vector). The table, M^-1 and magnitude over roughness and view,
 * is lab/fit's fit (ltc_table.h, which states its error). The Fresnel is v1's exact blend
 * (principled.h) at the half vector of v and the light's mean direction in the lobe: M times the
 * transformed polygon's vector irradiance. The highlight is then scaled by the lobe over the fitted
 * LTC at that direction (ltc_tail_correction), which corrects the fit's tails. A disk is its
 * area-matched LTC_DISK_SIDES-gon. docs/shading.md "Principled under area lights" gives the measured
 * error against the reference and against Cycles. */
#ifndef PHONGCL_AREA_LTC_H
#define PHONGCL_AREA_LTC_H

#include "area_light.h"
#include "ltc_table.h"
#include "principled.h"

/* Sides of the area-matched polygon that stands in for a disk. */
#define LTC_DISK_SIDES 32
#define LTC_DISK_STRETCH sqrt(2 * AREA_PI / (LTC_DISK_SIDES * sinpi((real)2 / LTC_DISK_SIDES)))

/* One lane's table entry, bilinear between the nodes: roughness i / (N - 1), sqrt(1 - cos view) j / (N - 1). */
void ltc_entry(real roughness, real cos_view, real* entry) {
  const real last = LTC_TABLE_SIZE - 1;
  const real x = clamp(roughness, (real)0, (real)1) * last;
  const real y = sqrt(clamp(1 - cos_view, (real)0, (real)1)) * last;
  const int i = min((int)x, LTC_TABLE_SIZE - 2), j = min((int)y, LTC_TABLE_SIZE - 2);
  const real fx = x - i, fy = y - j;
  __constant const float* e00 = &ltc_table[(i * LTC_TABLE_SIZE + j) * LTC_ENTRY_FLOATS];
  __constant const float* e01 = e00 + LTC_ENTRY_FLOATS;
  __constant const float* e10 = e00 + LTC_TABLE_SIZE * LTC_ENTRY_FLOATS;
  __constant const float* e11 = e10 + LTC_ENTRY_FLOATS;
  for (int k = 0; k < LTC_ENTRY_FLOATS; ++k) {
    const real low = e00[k] + fy * (e01[k] - e00[k]), high = e10[k] + fy * (e11[k] - e10[k]);
    entry[k] = low + fx * (high - low);
  }
}

/* Each lane's entry: M^-1 as m00, m02, m20, m22 (m11 = 1, the others 0) and the magnitude. */
typedef struct {
  realv m00, m02, m20, m22, magnitude;
} LtcEntry;

LtcEntry ltc_lookup(realv roughness, realv cos_view) {
  LtcEntry e;
#if PHONGCL_LANES == 1
  real entry[LTC_ENTRY_FLOATS];
  ltc_entry(roughness, cos_view, entry);
  e.m00 = entry[0], e.m02 = entry[1], e.m20 = entry[2], e.m22 = entry[3], e.magnitude = entry[4];
#else
  /* lane by lane: OpenCL C has no vector gather */
  real roughnesses[PHONGCL_LANES], cosines[PHONGCL_LANES], fields[LTC_ENTRY_FLOATS][PHONGCL_LANES];
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(roughness, 0, roughnesses);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(cos_view, 0, cosines);
  for (int lane = 0; lane < PHONGCL_LANES; ++lane) {
    real entry[LTC_ENTRY_FLOATS];
    ltc_entry(roughnesses[lane], cosines[lane], entry);
    for (int k = 0; k < LTC_ENTRY_FLOATS; ++k) fields[k][lane] = entry[k];
  }
  e.m00 = VLOAD(0, fields[0]), e.m02 = VLOAD(0, fields[1]), e.m20 = VLOAD(0, fields[2]);
  e.m22 = VLOAD(0, fields[3]), e.magnitude = VLOAD(0, fields[4]);
#endif
  return e;
}

/* The vector irradiance of a polygon clipped to z >= 0 as its edges come: half the sum over the
 * edges of the angle each subtends times the unit normal of its plane. Its z is the clamped
 * cosine's integral; its direction the light's mean direction. */
typedef struct {
  vec3 sum;
  PlaneCrossings horizon;
} VectorIrradiance;

vec3 edge_vector(vec3 a, vec3 b) {
  const vec3 normal = cross3(a, b);
  const realv sine = sqrt(dot3(normal, normal));
  return scale3(normal, SELECT(sine > 0, atan2(sine, dot3(a, b)) / sine, 0));
}

void add_vector_edge(VectorIrradiance* f, vec3 a, vec3 b) {
  const realv zero = 0, one = 1;
  const ClippedEdge above = clip_edge(a, b, make_vec3(zero, zero, one));
  f->sum = add3(f->sum, scale3(edge_vector(above.a, above.b), edge_kept(&above)));
  note_crossing(&f->horizon, &above);
}

/* The finished sum; edges counter-clockwise about the emitter's normal run clockwise seen from P. */
vec3 vector_irradiance(const VectorIrradiance* f) {
  const vec3 horizon = scale3(edge_vector(f->horizon.exit, f->horizon.entry), f->horizon.crosses);
  return scale3(add3(f->sum, horizon), (real)-0.5);
}

/* M^-1 x for x given in the frame (tangent, bitangent, n). */
vec3 ltc_space(const LtcEntry* e, vec3 tangent, vec3 bitangent, vec3 n, vec3 x) {
  const realv lx = dot3(tangent, x), lz = dot3(n, x);
  return make_vec3(fma(e->m00, lx, e->m02 * lz), dot3(bitangent, x), fma(e->m20, lx, e->m22 * lz));
}

/* The fitted lobe's value towards unit w in the lobe's frame, in the units of the lobe's own (pi f
 * n.l without Fresnel): magnitude times the clamped cosine over pi at M^-1 w / |M^-1 w| times |det
 * M^-1| / |M^-1 w|^3, pi cancelled; M^-1's scale cancels too (m11 = 1 here). */
static inline realv ltc_value(const LtcEntry* e, realv det, vec3 w) {
  const realv zero = 0, one = 1;
  const vec3 warped = ltc_space(e, make_vec3(one, zero, zero), make_vec3(zero, one, zero), make_vec3(zero, zero, one), w);
  const realv length_sq = dot3(warped, warped);
  return e->magnitude * det * fmax(warped.z, 0) / fmax(length_sq * length_sq, (real)1e-30f);
}

/* What the LTC misses where the emitter is: the lobe over the fitted LTC at the light's mean direction
 * in the lobe. One transformed cosine cannot follow GGX's long tail (2x off there at roughness 0.3),
 * but over an emitter in the tail both vary slowly, so their ratio at the mean direction is their
 * integrals' ratio. Weighted towards 1 by `caught`, the share of the LTC's mass on the emitter: one
 * that holds the peak is where the fit is good and one direction's ratio is not the integrals'. */
static inline realv ltc_tail_correction(const LtcEntry* e, realv det, PrincipledSurface m, vec3 v_local, vec3 mean,
                                        realv caught) {
  const realv zero = 0, one = 1;
  PrincipledSurface white = m; /* f0 = 1 takes no Fresnel: the response is the lobe the table fits */
  white.specular_color = make_vec3(one, one, one);
  white.f0 = one;
  const realv lobe = principled_response(white, make_vec3(zero, zero, one), v_local, mean).specular.x;
  const realv fitted = ltc_value(e, det, mean);
  const realv ratio = SELECT(fitted > 0 && lobe > 0, lobe / fitted, 1);
  return fma(1 - ratio, caught, ratio);
}

/* A Principled lane's highlight from an area light: `highlight` times the light's colour and `tint`. */
typedef struct {
  realv highlight;
  vec3 tint;
} LtcHighlight;

/* The highlight of one area light, times its range window, for pixels at p (relative to the eye)
 * with unit normal n and unit vector to the eye `view`. */
LtcHighlight ltc_area_highlight(UNIFORM_SPACE const AreaLightRecord* light, vec3 p, vec3 n, vec3 view,
                                PrincipledSurface m) {
  const vec3 c_eye = sub3(area_vector(light->center), p);
  const realv distance = sqrt(dot3(c_eye, c_eye));
  /* only directions matter: the geometry scaled to keep its products far from float's limits */
  const float extent = length((float3)(light->axis_u[0], light->axis_u[1], light->axis_u[2])) +
                       length((float3)(light->axis_v[0], light->axis_v[1], light->axis_v[2]));
  const realv scale = 1 / (distance + extent);
  const vec3 c = scale3(c_eye, scale);
  const vec3 u = scale3(area_vector(light->axis_u), scale), v = scale3(area_vector(light->axis_v), scale);
  const realv h = -dot3(c, area_vector(light->normal)); /* P's height above the emitting side */
  /* the frame: x towards the eye in the tangent plane (any tangent where the eye is on the normal) */
  const realv n_dot_v = dot3(n, view);
  const vec3 along = sub3(view, scale3(n, n_dot_v));
  const realv along_sq = dot3(along, along);
  const realv zero = 0, one = 1;
  const vec3 axis = select3(make_vec3(one, zero, zero), make_vec3(zero, one, zero), SELECT(fabs(n.x) < (real)0.5, 1, 0));
  const vec3 fallback = sub3(axis, scale3(n, dot3(n, axis)));
  const vec3 tangent_raw = select3(along, fallback, SELECT(along_sq > (real)1e-12f, 1, 0));
  const vec3 tangent = scale3(tangent_raw, rsqrt(fmax(dot3(tangent_raw, tangent_raw), (real)1e-30f)));
  const vec3 bitangent = cross3(n, tangent);
  const LtcEntry e = ltc_lookup(m.roughness, n_dot_v);
  VectorIrradiance f = {make_vec3(zero, zero, zero), no_crossings()};
  const int sides = light->shape == AREA_RECT ? 4 : LTC_DISK_SIDES;
  /* The emitter clipped to the surface's horizon first, where the lobe ends (the LTC's support, the
   * transformed hemisphere, reaches past it), then in the LTC's space to its hemisphere. */
  PlaneCrossings horizon = no_crossings();
  vec3 previous = emitter_vertex(light->shape, c, u, v, 0, sides, LTC_DISK_STRETCH);
  for (int k = 1; k <= sides; ++k) {
    const vec3 next = emitter_vertex(light->shape, c, u, v, k % sides, sides, LTC_DISK_STRETCH);
    const ClippedEdge above = clip_edge(previous, next, n); /* an edge wholly below: a point, adding 0 */
    note_crossing(&horizon, &above);
    add_vector_edge(&f, ltc_space(&e, tangent, bitangent, n, above.a), ltc_space(&e, tangent, bitangent, n, above.b));
    previous = next;
  }
  /* the horizon's own edge (0 to 0, adding nothing, where the emitter is not cut) */
  add_vector_edge(&f, ltc_space(&e, tangent, bitangent, n, horizon.exit), ltc_space(&e, tangent, bitangent, n, horizon.entry));
  const vec3 irradiance = vector_irradiance(&f);
  /* The mean direction back in the lobe's frame: M = (M^-1)^-1, its 2x2 block's inverse up to a
   * positive factor; then v1's Fresnel at its half vector with v = (sin, 0, cos). */
  const realv det = e.m00 * e.m22 - e.m02 * e.m20;
  vec3 mean = make_vec3(e.m22 * irradiance.x - e.m02 * irradiance.z, det * irradiance.y,
                        e.m00 * irradiance.z - e.m20 * irradiance.x);
  mean = scale3(mean, rsqrt(fmax(dot3(mean, mean), (real)1e-30f)));
  const vec3 v_local = make_vec3(sqrt(fmax(1 - n_dot_v * n_dot_v, (real)0)), zero, n_dot_v);
  const vec3 half_sum = add3(v_local, mean);
  const realv l_dot_h = dot3(mean, half_sum) * rsqrt(fmax(dot3(half_sum, half_sum), (real)1e-30f));
  const realv fh = fresnel_blend(m, l_dot_h);
  const realv caught = clamp(irradiance.z / AREA_PI, (real)0, (real)1);
  const realv tail = ltc_tail_correction(&e, det, m, v_local, mean, caught);
  LtcHighlight result;
  result.tint = make_vec3(fma(1 - fh, m.specular_color.x, fh), fma(1 - fh, m.specular_color.y, fh),
                          fma(1 - fh, m.specular_color.z, fh));
  const realv lit = SELECT(h > 0 && n_dot_v > 0, 1, 0);
  result.highlight = SELECT(lit != 0, tail * e.magnitude * fmax(irradiance.z, 0), 0) * area_range_window(light, distance);
  return result;
}

#endif
