/* Small vector math for the Phong kernel, robust on degenerate inputs. Included by phong.cl and by
 * the stability kernel (kernels/stability.cl), so the catalogue tests exactly the code that shades. */
#ifndef PHONGCL_PHONG_MATH_H
#define PHONGCL_PHONG_MATH_H

#ifdef PHONGCL_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
#else
typedef float real;
#endif

/* A plain struct, not float3: it is scalarised, so PoCL vectorises across work-items. */
typedef struct {
  real x, y, z;
} vec3;

inline vec3 make_vec3(real x, real y, real z) {
  vec3 v = {x, y, z};
  return v;
}
inline vec3 sub3(vec3 a, vec3 b) { return make_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
inline vec3 scale3(vec3 a, real s) { return make_vec3(a.x * s, a.y * s, a.z * s); }
inline real dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

#ifdef PHONGCL_FAST
/* Fast variant: no rescaling, native reciprocal square root. Zero stays zero; components whose
 * squares overflow or underflow float lose the direction (the cost of this variant). */
inline vec3 unit_or_zero(vec3 v) {
  real length_sq = dot3(v, v);
  return length_sq > 0 ? scale3(v, native_rsqrt(length_sq)) : make_vec3(0, 0, 0);
}
#else
/* normalize() that neither overflows nor underflows: divide by the largest |component| first, so
 * components of 1e30 (squares overflow float) or 1e-40 (squares vanish) still give a unit vector.
 * A zero vector stays zero: the documented policy for degenerate inputs (README). */
inline vec3 unit_or_zero(vec3 v) {
  real largest = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
  if (!(largest > 0)) return make_vec3(0, 0, 0);
  vec3 scaled = make_vec3(v.x / largest, v.y / largest, v.z / largest);
  return scale3(scaled, rsqrt(dot3(scaled, scaled)));
}
#endif

/* max(0, v.r)^q with pow(0, 0) = 1 (OpenCL powr(0, 0) is NaN, so no powr).
 * Near the highlight peak v.r rounds towards 1 and x^q multiplies that rounding error by q, so the
 * logarithm is taken from one_minus_cos = 1 - v.r, which the caller computes without cancellation
 * as |v - r|^2 / 2 (v and r unit vectors). Far from the peak, log(v.r) is the accurate one. */
inline real specular_power(real cos_vr, real one_minus_cos, real q) {
  if (q == 0) return 1;
  if (!(cos_vr > 0)) return 0;
#ifdef PHONGCL_FAST
  return native_exp2(q * native_log2(cos_vr));
#else
  real log_base = one_minus_cos < (real)0.5 ? log1p(-one_minus_cos) : log(cos_vr);
  return exp(q * log_base);
#endif
}

#endif
