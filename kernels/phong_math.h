/* Small vector math for the Phong kernel, robust on degenerate inputs, written once for any lane
 * count. A work-item shades PHONGCL_LANES pixels at once as OpenCL vectors (floatN): PoCL's
 * implicit work-item vectoriser gives up on this kernel (its SLP pass first packs the x/y/z math
 * into short vectors), while explicit floatN code compiles to full-width SIMD with vectorised
 * exp2/log2. PHONGCL_LANES=1 is the plain scalar kernel for GPUs. */
#ifndef PHONGCL_PHONG_MATH_H
#define PHONGCL_PHONG_MATH_H

#ifndef PHONGCL_LANES
#define PHONGCL_LANES 1
#endif

#define PHONGCL_CAT(a, b) a##b
#define PHONGCL_XCAT(a, b) PHONGCL_CAT(a, b)

#ifdef PHONGCL_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define PHONGCL_REAL double
#else
#define PHONGCL_REAL float
#endif
typedef PHONGCL_REAL real;

#if PHONGCL_LANES == 1
typedef real realv; /* one pixel's value */
typedef float floatv;
typedef int intv;
#define VLOAD_FLOAT(i, p) ((p)[i])
#define VLOAD_HALF(i, p) vload_half(i, p)
#define VLOAD_INT(i, p) ((p)[i])
#define VSTORE_FLOAT(v, i, p) ((p)[i] = (v))
#define TO_REALV(x) ((real)(x))
#define TO_FLOATV(x) ((float)(x))
#define ANY_LANE(condition) (condition)
#else
typedef PHONGCL_XCAT(PHONGCL_REAL, PHONGCL_LANES) realv;
typedef PHONGCL_XCAT(float, PHONGCL_LANES) floatv;
typedef PHONGCL_XCAT(int, PHONGCL_LANES) intv;
#define VLOAD_FLOAT(i, p) PHONGCL_XCAT(vload, PHONGCL_LANES)(i, p)
#define VLOAD_HALF(i, p) PHONGCL_XCAT(vload_half, PHONGCL_LANES)(i, p)
#define VLOAD_INT(i, p) PHONGCL_XCAT(vload, PHONGCL_LANES)(i, p)
#define VSTORE_FLOAT(v, i, p) PHONGCL_XCAT(vstore, PHONGCL_LANES)(v, i, p)
#define TO_REALV(x) PHONGCL_XCAT(PHONGCL_XCAT(convert_, PHONGCL_REAL), PHONGCL_LANES)(x)
#define TO_FLOATV(x) PHONGCL_XCAT(convert_float, PHONGCL_LANES)(x)
#define ANY_LANE(condition) any(condition)
#endif

/* Per-lane choice without branches: `condition` is a comparison of realv values. */
#define SELECT(condition, if_true, if_false) ((condition) ? (realv)(if_true) : (realv)(if_false))

/* A plain struct of lanes, not float3: float3 math does not vectorise on PoCL. */
typedef struct {
  realv x, y, z;
} vec3;

inline vec3 make_vec3(realv x, realv y, realv z) {
  vec3 v = {x, y, z};
  return v;
}
inline vec3 sub3(vec3 a, vec3 b) { return make_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
inline vec3 scale3(vec3 a, realv s) { return make_vec3(a.x * s, a.y * s, a.z * s); }
inline realv dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

#ifdef PHONGCL_FAST
/* Fast variant: no rescaling, native reciprocal square root. Zero stays zero; components whose
 * squares overflow or underflow float lose the direction (the cost of this variant). */
inline vec3 unit_or_zero(vec3 v) {
  realv length_sq = dot3(v, v);
  /* FLT_MIN, not 0: under -cl-fast-relaxed-math a denormal length_sq (components ~1e-23) may be
   * flushed inside native_rsqrt, giving Inf and then NaN; such a vector is treated as zero. */
  return scale3(v, SELECT(length_sq >= FLT_MIN, native_rsqrt(length_sq), 0));
}
#else
/* normalize() that neither overflows nor underflows: divide by the largest |component| first, so
 * components of 1e30 (squares overflow float) or 1e-40 (squares vanish) still give a unit vector.
 * A zero vector stays zero: the documented policy for degenerate inputs (README). */
inline vec3 unit_or_zero_rescaled(vec3 v) {
  realv largest = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
  realv nonzero = SELECT(largest > 0, largest, 1);
  vec3 scaled = make_vec3(v.x / nonzero, v.y / nonzero, v.z / nonzero);
  realv length_sq = dot3(scaled, scaled);
  return scale3(scaled, SELECT(length_sq > 0, rsqrt(length_sq), 0));
}

/* The same result, cheaply when every lane's squared length is comfortably inside the normal
 * range (the rescaling costs three divisions); the rescaled path only when a lane needs it. */
inline vec3 unit_or_zero(vec3 v) {
  const realv length_sq = dot3(v, v);
  const real lowest = 1e-30f, highest = 1e30f;
  if (ANY_LANE(!(length_sq >= lowest && length_sq <= highest))) return unit_or_zero_rescaled(v);
  return scale3(v, rsqrt(length_sq));
}
#endif

/* log2 of the specular base, one vectorised log2 per lane. Near the peak (e = 1 - v.r < 0.5) it is
 * log2(1 - e) to a few ulp: u = 1 - e rounds, but log2(u) * e / (1 - u) corrects for the rounding
 * (Goldberg's log1p trick), and u == 1 only when e is below half an ulp of 1, where
 * log2(1 - e) = -e / ln 2 to float precision. Elsewhere log2(cos_vr) is the accurate one. */
inline realv log2_specular_base(realv cos_vr, realv e) {
  const realv u = 1 - e;
  const realv near_peak = SELECT(e < (real)0.5, 1, 0);
  const realv logarithm = log2(SELECT(near_peak != 0, u, cos_vr));
  const realv corrected = SELECT(near_peak != 0 && u != 1, logarithm * (e / (1 - u)), logarithm);
  return SELECT(near_peak != 0 && u == 1, -e * (real)M_LOG2E, corrected);
}

/* max(0, v.r)^q with pow(0, 0) = 1 (OpenCL powr(0, 0) is NaN, so no powr).
 * Near the highlight peak v.r rounds towards 1 and x^q multiplies that rounding error by q, so the
 * logarithm is taken from one_minus_cos = 1 - v.r, which the caller computes without cancellation
 * as |v - r|^2 / 2 (v and r unit vectors). Far from the peak, log2(v.r) is the accurate one.
 * exp2/log2 rather than pow or exp/log1p: PoCL vectorises those, not the others. */
inline realv specular_power(realv cos_vr, realv one_minus_cos, realv q) {
#ifdef PHONGCL_FAST
  realv power = native_exp2(q * native_log2(cos_vr));
#else
  realv power = exp2(q * log2_specular_base(cos_vr, one_minus_cos));
#endif
  return SELECT(q == 0, 1, SELECT(cos_vr > 0, power, 0));
}

#endif
