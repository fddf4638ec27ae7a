/* Small vector math for the Phong kernel, robust on degenerate inputs, written once for any lane
 * count. A work-item shades PHONGCL_LANES pixels at once as OpenCL vectors (floatN): PoCL's
 * implicit work-item vectoriser gives up on this kernel (its SLP pass first packs the x/y/z math
 * into short vectors), while explicit floatN code compiles to full-width SIMD. PHONGCL_LANES=1 is
 * the plain scalar kernel for GPUs. */
#ifndef PHONGCL_PHONG_MATH_H
#define PHONGCL_PHONG_MATH_H

/* Linkage, here and in every kernel file. A helper is a plain function: defined once, with external
 * linkage, so every compiler finds it, unoptimised too (a C99 `inline` definition is not one), and
 * the compiler inlines it where it judges that pays. Code split out of its one caller for reading
 * (phong.cl's steps, one-line wrappers) is `static inline`: inlined in place, as if written there.
 * Together they keep the generated code, and the fast variant's roundings, those of the kernel
 * written in one piece (docs/kernel.md). */

#if !defined(PHONGCL_LANES) || !defined(PHONGCL_DOUBLE) || !defined(PHONGCL_FAST)
#error "phong_math.h needs PHONGCL_LANES, PHONGCL_DOUBLE and PHONGCL_FAST defined (features.h)"
#endif
#if PHONGCL_LANES != 1 && PHONGCL_LANES != 2 && PHONGCL_LANES != 4 && PHONGCL_LANES != 8 && PHONGCL_LANES != 16
#error "PHONGCL_LANES must be 1, 2, 4, 8 or 16 (OpenCL vector widths)"
#endif

#define PHONGCL_CAT(a, b) a##b
#define PHONGCL_XCAT(a, b) PHONGCL_CAT(a, b)

#if PHONGCL_DOUBLE
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
#define VLOAD(i, p) ((p)[i])
#define VLOAD_HALF(i, p) vload_half(i, p)
#define VSTORE(v, i, p) ((p)[i] = (v))
#define TO_REALV(x) ((real)(x))
#define TO_FLOATV(x) ((float)(x))
#define AS_INTV(x) as_int(x)
#define AS_UINTV(x) as_uint(x)
#define AS_FLOATV(x) as_float(x)
#define INT_TO_FLOATV(x) convert_float(x)
#else
typedef PHONGCL_XCAT(PHONGCL_REAL, PHONGCL_LANES) realv;
typedef PHONGCL_XCAT(float, PHONGCL_LANES) floatv;
typedef PHONGCL_XCAT(int, PHONGCL_LANES) intv;
#define VLOAD(i, p) PHONGCL_XCAT(vload, PHONGCL_LANES)(i, p)
#define VLOAD_HALF(i, p) PHONGCL_XCAT(vload_half, PHONGCL_LANES)(i, p)
#define VSTORE(v, i, p) PHONGCL_XCAT(vstore, PHONGCL_LANES)(v, i, p)
#define TO_REALV(x) PHONGCL_XCAT(PHONGCL_XCAT(convert_, PHONGCL_REAL), PHONGCL_LANES)(x)
#define TO_FLOATV(x) PHONGCL_XCAT(convert_float, PHONGCL_LANES)(x)
#define AS_INTV(x) PHONGCL_XCAT(as_int, PHONGCL_LANES)(x)
#define AS_UINTV(x) PHONGCL_XCAT(as_uint, PHONGCL_LANES)(x)
#define AS_FLOATV(x) PHONGCL_XCAT(as_float, PHONGCL_LANES)(x)
#define INT_TO_FLOATV(x) PHONGCL_XCAT(convert_float, PHONGCL_LANES)(x)
#endif

/* A comparison of realv values as an intv mask (double comparisons give long lanes). */
#if PHONGCL_LANES > 1 && PHONGCL_DOUBLE
#define LANE_MASK(comparison) PHONGCL_XCAT(convert_int, PHONGCL_LANES)(comparison)
#else
#define LANE_MASK(comparison) (comparison)
#endif

/* A vector's lanes combined by a two-operand `op` (a macro or function), by halving the vector:
 * op(v.lo, v.hi) until one lane is left. */
#define HALVE_LANES(v, op) op((v).lo, (v).hi)
#if PHONGCL_LANES == 1
#define REDUCE_LANES(v, op) (v)
#elif PHONGCL_LANES == 2
#define REDUCE_LANES(v, op) HALVE_LANES(v, op)
#elif PHONGCL_LANES == 4
#define REDUCE_LANES(v, op) HALVE_LANES(HALVE_LANES(v, op), op)
#elif PHONGCL_LANES == 8
#define REDUCE_LANES(v, op) HALVE_LANES(HALVE_LANES(HALVE_LANES(v, op), op), op)
#elif PHONGCL_LANES == 16
#define REDUCE_LANES(v, op) HALVE_LANES(HALVE_LANES(HALVE_LANES(HALVE_LANES(v, op), op), op), op)
#else
#error "REDUCE_LANES: no reduction for this PHONGCL_LANES"
#endif
#define BITWISE_AND(a, b) ((a) & (b))

/* Whether every lane of a mask is true. PoCL's all() and any() test the lanes one by one, each
 * with a branch; Clang's reduction of the mask compiles to one mask test (kortestw with AVX-512,
 * against eleven instructions for the halving below), and other compilers halve the vector with ANDs. */
#if PHONGCL_LANES > 1 && defined(__has_builtin)
#if __has_builtin(__builtin_reduce_and)
#define PHONGCL_REDUCE_AND(mask) __builtin_reduce_and(mask)
#endif
#endif
#ifndef PHONGCL_REDUCE_AND
#define PHONGCL_REDUCE_AND(mask) REDUCE_LANES(mask, BITWISE_AND)
#endif
int all_lanes(intv mask) { return PHONGCL_REDUCE_AND(mask) != 0; }
/* Some lane of a realv comparison holds. */
#define ANY_LANE(comparison) (!all_lanes(LANE_MASK(!(comparison))))

/* Per-lane choice without branches: `condition` is a comparison of realv values. */
#define SELECT(condition, if_true, if_false) ((condition) ? (realv)(if_true) : (realv)(if_false))

/* A plain struct of lanes, not float3: float3 math does not vectorise on PoCL. */
typedef struct {
  realv x, y, z;
} vec3;

vec3 make_vec3(realv x, realv y, realv z) {
  vec3 v = {x, y, z};
  return v;
}
vec3 sub3(vec3 a, vec3 b) { return make_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
vec3 scale3(vec3 a, realv s) { return make_vec3(a.x * s, a.y * s, a.z * s); }
realv dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 add3(vec3 a, vec3 b) { return make_vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
vec3 cross3(vec3 a, vec3 b) {
  return make_vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* if_true in the lanes where condition != 0, else if_false. */
vec3 select3(vec3 if_true, vec3 if_false, realv condition) {
  return make_vec3(SELECT(condition != 0, if_true.x, if_false.x), SELECT(condition != 0, if_true.y, if_false.y),
                   SELECT(condition != 0, if_true.z, if_false.z));
}

realv largest_magnitude(vec3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }

#if PHONGCL_DOUBLE
/* v divided by its largest |component| (v itself when zero). */
vec3 rescaled(vec3 v) {
  const realv largest = largest_magnitude(v);
  const realv nonzero = SELECT(largest > 0, largest, 1);
  return make_vec3(v.x / nonzero, v.y / nonzero, v.z / nonzero);
}

/* q * log2 of the specular base, one log2 per lane. Near the peak (e = 1 - v.r < 0.5) it is
 * log2(1 - e) to a few ulp: u = 1 - e rounds, but log2(u) * e / (1 - u) corrects for the rounding
 * (Goldberg's log1p trick), and u == 1 only when e is below half an ulp of 1, where
 * log2(1 - e) = -e / ln 2 to double precision. Elsewhere log2(cos_vr) is the accurate one. */
realv specular_exponent(realv cos_vr, realv e, realv q) {
  const realv u = 1 - e;
  const realv near_peak = SELECT(e < (real)0.5, 1, 0);
  const realv logarithm = log2(SELECT(near_peak != 0, u, cos_vr));
  const realv corrected = SELECT(near_peak != 0 && u != 1, logarithm * (e / (1 - u)), logarithm);
  return q * SELECT(near_peak != 0 && u == 1, -e * (real)M_LOG2E, corrected);
}
realv exp2_nonpositive(realv y) { return exp2(y); }
#else
/* v scaled by the power of two that brings its largest |component| into [1, 2) (near 1 for the
 * extremes: subnormals, the top two exponents), from the exponent bits: exact, and no branches or
 * divisions. */
vec3 rescaled(vec3 v) {
  /* |x| as bits orders like |x| (non-negative floats); NaN and Inf give the largest exponent. */
  const intv largest = max(AS_INTV(fabs(v.x)), max(AS_INTV(fabs(v.y)), AS_INTV(fabs(v.z))));
  /* 2^(127 - e) stays a normal float. A vector bound: Oclgrind 21.10 gets min(intn, int) wrong. */
  const intv exponent = min(largest >> 23, (intv)253);
  return scale3(v, AS_FLOATV((254 - exponent) << 23));
}

/* Where specular_exponent() takes the logarithm of 1 - e itself, for e below this, rather than of the cosine. */
#define PHONGCL_NEAR_PEAK 0.29f

/* q * log2(1 - e) for 0 <= e < 1, as straight-line code (PoCL's log2 is a table lookup with scalar
 * gathers, and a call that spills every vector register). Cephes logf: x = 2^k f, f in
 * [sqrt(1/2), sqrt(2)), ln f = m - m^2/2 + m^3 P(m) with m = f - 1 exact, about 1 ulp.
 * Near the peak (e < 0.29) m = -e itself: no rounding of 1 - e, whose error x^q would multiply
 * by q. Far from the peak the base is cos_vr = v.r as the caller computed it.
 * The light loop is latency-bound, so the reduction has no compares (the bits are offset by those
 * of sqrt(1/2), musl's way), the polynomial is in Estrin's form (half the depth of Horner's), and
 * q is folded into the last two steps. */
realv specular_exponent(realv cos_vr, realv e, realv q) {
  /* cos_vr * 2^23 is exact and a normal float even where cos_vr is subnormal. */
  /* Unsigned arithmetic: where cos_vr <= 0 (selected away below) the difference wraps. */
  const intv offset_bits = AS_INTV(AS_UINTV(cos_vr * 0x1p23f) - 0x3f3504f3u);
  const intv exponent = (offset_bits >> 23) - 23;
  const realv f = AS_FLOATV((offset_bits & 0x007fffff) + 0x3f3504f3);
  const intv near_peak = e < PHONGCL_NEAR_PEAK;
  const realv m = SELECT(near_peak, -e, f - 1);
  const realv qk = SELECT(near_peak, 0, q * INT_TO_FLOATV(exponent));
  const realv q_log2e = q * M_LOG2E_F;
  const realv m2 = m * m, m4 = m2 * m2, m5 = m4 * m;
  const realv p01 = 3.3333331174E-1f - 2.4999993993E-1f * m, p23 = 2.0000714765E-1f - 1.6668057665E-1f * m;
  const realv p45 = 1.4249322787E-1f - 1.2420140846E-1f * m, p67 = 1.1676998740E-1f - 1.1514610310E-1f * m;
  const realv low = p01 + m2 * p23, high = (p45 + m2 * p67) + m4 * 7.0376836292E-2f; /* P = low + m^4 high */
  const realv mp_minus_half = m5 * high + (m * low - 0.5f);                          /* m P(m) - 1/2 */
  /* q (k + log2(e) (m + m^2 (m P - 1/2))) */
  return (m2 * q_log2e) * mp_minus_half + (m * q_log2e + qk);
}

/* 2^y for y <= 0 (Cephes exp2f on the fraction, about 1 ulp), and 0 where 2^y is below the
 * smallest normal float, 2^-126: subnormal results cost a microcode assist per operation on x86
 * (half the frame's time at 16 lights) and GPUs flush them anyway. The rounding to an integer goes
 * through the bits of y + 1.5 * 2^23, which -cl-fast-relaxed-math cannot fold away. */
realv exp2_nonpositive(realv y) {
  /* Unsigned arithmetic: y far below -126 (selected away below) wraps rather than overflows. */
  const intv k = AS_INTV(AS_UINTV(y + 0x1.8p23f) - 0x4b400000u); /* nearest integer */
  const realv r = y - INT_TO_FLOATV(k);                /* [-0.5, 0.5], exact */
  const realv r2 = r * r;
  const realv p = (6.931472028550421E-1f + 2.402264791363012E-1f * r) +
                  r2 * ((5.550332471162809E-2f + 9.618437357674640E-3f * r) +
                        r2 * (1.339887440266574E-3f + 1.535336188319500E-4f * r));
  const realv scale = AS_FLOATV((AS_UINTV(k) + 127u) << 23); /* 2^k */
  return SELECT(y >= -126.0f, scale + (r * scale) * p, 0);
}
#endif

/* 1 / |v| for a rescaled v, 0 for the zero vector. */
realv inverse_length(vec3 scaled) {
  const realv length_sq = dot3(scaled, scaled);
  return SELECT(length_sq > 0, rsqrt(length_sq), 0);
}

/* 1 / sqrt(x) for x in [2^-100, 2^100]. PoCL's rsqrt and native_rsqrt are a square root and a
 * division, some 37 cycles on the light loop's chain; with AVX-512 it is the hardware's estimate
 * (2^-14) and one Newton step instead, about 1 ulp: r + r (1 - x r^2) / 2, 1 - x r^2 from an fma. */
#if !PHONGCL_DOUBLE && PHONGCL_LANES == 16 && defined(__AVX512F__)
realv inverse_sqrt_in_range(realv x) {
  const realv estimate = __builtin_ia32_rsqrt14ps512_mask(x, (realv)0, (ushort)0xffff);
  return fma(estimate * 0.5f, fma(-x * estimate, estimate, (realv)1), estimate);
}
#else
realv inverse_sqrt_in_range(realv x) { return rsqrt(x); }
#endif

/* 1 / |v|, where |v|^2 is comfortably inside float's range in every lane; elsewhere v is replaced
 * by rescaled(v) first. The check is a branch, predicted taken: in the latency-bound light loop it
 * keeps the rescaling off each light's dependency chain. */
realv inverse_length_in_range(vec3* v) {
  const realv length_sq = dot3(*v, *v);
  if (all_lanes(LANE_MASK(length_sq >= 0x1p-100f && length_sq <= 0x1p100f))) return inverse_sqrt_in_range(length_sq);
  *v = rescaled(*v);
  return inverse_length(*v);
}

/* inverse_length_in_range() that also gives the length d = |v| and 1/d, for a light's falloff and
 * range: where v had to be rescaled they come from the scale, exact powers of two. A zero v gives
 * d = 0 and 1/d = 0 (its light adds nothing: n.l is 0); a d beyond float gives +Inf and 0. */
realv distance_in_range(vec3* v, realv* distance, realv* inverse_distance) {
  const realv length_sq = dot3(*v, *v);
  if (all_lanes(LANE_MASK(length_sq >= 0x1p-100f && length_sq <= 0x1p100f))) {
    const realv inverse = inverse_sqrt_in_range(length_sq);
    *distance = length_sq * inverse;
    *inverse_distance = inverse;
    return inverse;
  }
  const realv largest = largest_magnitude(*v);
  *v = rescaled(*v);
  const realv inverse = inverse_length(*v);
  const realv unscale = SELECT(largest > 0, largest / largest_magnitude(*v), 0); /* |v| = unscale * |rescaled| */
  *distance = SELECT(inverse > 0, unscale / inverse, 0);
  *inverse_distance = SELECT(largest > 0, inverse / unscale, 0);
  return inverse;
}

/* normalize() that neither overflows nor underflows: components of 1e30 (squares overflow float)
 * or 1e-40 (squares vanish) still give a unit vector. A zero vector stays zero: the documented
 * policy for degenerate inputs (docs/shading.md "Degenerate inputs"). */
vec3 unit_or_zero(vec3 v) {
  const vec3 scaled = rescaled(v);
  return scale3(scaled, inverse_length(scaled));
}

/* max(0, v.r)^q with pow(0, 0) = 1 (OpenCL powr(0, 0) is NaN, so no powr).
 * Near the highlight peak v.r rounds towards 1 and x^q multiplies that rounding error by q, so the
 * logarithm is taken from one_minus_cos = 1 - v.r, which the caller computes without cancellation
 * as |v - r|^2 / 2 (v and r unit vectors). Far from the peak, log2(v.r) is the accurate one. */
realv specular_power(realv cos_vr, realv one_minus_cos, realv q) {
  const realv power = exp2_nonpositive(specular_exponent(cos_vr, one_minus_cos, q));
  return SELECT(q == 0, 1, SELECT(cos_vr > 0, power, 0));
}

/* A lobe's cosine and 1 - cosine, the latter computed without cancellation: specular_power()'s arguments. */
typedef struct {
  realv cosine, one_minus_cosine;
} LobeCosine;

/* The cosine below which specular_power(cosine, 1 - cosine, q) is certainly 0, so that the light
 * loop can leave the power out where no lane's cosine reaches it; -MAXFLOAT where q = 0 (the power
 * is 1 everywhere). A cosine <= 0 gives 0 in every variant (specular_power's select), and double
 * keeps subnormals, so that is its cutoff. In float the power is 0 below 2^-126, and a cosine below
 * 2^(-128 / q) takes it there with a factor of 4 to spare (the power's error is a few ulp) where the
 * logarithm comes from the cosine: below 0.7, where 1 - cosine of unit vectors is above
 * PHONGCL_NEAR_PEAK. Nearer the peak it comes from 1 - cosine, whose rounding a cutoff on the cosine
 * does not bound, so the cutoff is at most 0.7. */
#if PHONGCL_DOUBLE
realv highlight_cutoff(realv q) { return SELECT(q > 0, 0, -MAXFLOAT); }
#else
realv highlight_cutoff(realv q) { return SELECT(q > 0, fmin(exp2_nonpositive(-128 / q), 0.7f), -MAXFLOAT); }
#endif

/* sum += value, with the rounding error carried in compensation (Kahan). Where a value can be +Inf
 * (`infinite_values`), Inf - Inf would make the compensation NaN: it is kept 0 there, and the sum +Inf. */
void kahan_add(realv* sum, realv* compensation, realv value, bool infinite_values) {
  const realv corrected = value - *compensation;
  const realv next = *sum + corrected;
  *compensation = infinite_values ? SELECT(next - next == 0, (next - *sum) - corrected, 0) : (next - *sum) - corrected;
  *sum = next;
}

/* Undoes the host's radiance scaling by 2^e = a * b (two power-of-two factors, each a normal
 * float): (value * a) * b is exact up to one rounding, and overflows only when the exact result
 * does. Under -cl-fast-relaxed-math the compiler may reassociate that into value * (a * b), and
 * a * b = 2^128 overflows (3e38 lights give +Inf for a finite 1.5e38, and 0 * Inf = NaN in dark
 * pixels), so the fast variant uses ldexp, which no flag rewrites. A vector exponent rather than
 * ldexp(floatn, int): Oclgrind 21.10 gets that overload's lanes wrong. */
floatv unscale(realv value, float a, float b) {
  if (PHONGCL_FAST) return TO_FLOATV(ldexp(value, (intv)(ilogb(a) + ilogb(b))));
  return TO_FLOATV(value * a * b);
}

/* Writes a work-item's vector of one output plane. The planes are written once and not read again
 * here: with Clang (PoCL) they are streamed past the caches, so no line is first read for ownership
 * (16 of the 20 bytes a pixel costs at 0 lights). Planes start at multiples of PHONGCL_LANES floats,
 * so the floatv is aligned. */
static inline void store_plane(floatv value, size_t group, __global float* plane) {
#if defined(__clang__) && PHONGCL_LANES > 1
  __builtin_nontemporal_store(value, (__global floatv*)plane + group);
#else
  VSTORE(value, group, plane);
#endif
}

#endif
