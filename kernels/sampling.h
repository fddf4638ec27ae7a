/* Low-discrepancy points in the unit square, decorrelated between pixels: the R2 sequence (the
 * rank-1 lattice of the plastic number g, point k = frac(k / g, k / g^2)), shifted per pixel by a
 * Cranley-Patterson rotation drawn from an integer hash of the pixel. Any prefix of N points is
 * stratified about as well as an N-point jittered grid, for every N, so a light's ray count need not
 * be a square; the rotation turns neighbouring pixels' structured error into noise.
 * Computed in 32-bit fixed point: k * A wraps modulo 2^32, which is frac() exactly for any k. */
#ifndef PHONGCL_SAMPLING_H
#define PHONGCL_SAMPLING_H

#include "phong_math.h"

#if PHONGCL_LANES == 1
typedef uint uintv;
#else
typedef PHONGCL_XCAT(uint, PHONGCL_LANES) uintv;
#endif

/* 2^32 / g and 2^32 / g^2, g = 1.32471795724474602596 (x^3 = x + 1), rounded. */
#define R2_STEP_U 3242174889u
#define R2_STEP_V 2447445414u

/* Chris Wellons' lowbias32: every input bit flips each output bit with probability near 1/2, so
 * pixel indices one apart give unrelated rotations. */
static inline uintv hash_uint(uintv x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/* Each lane's number: 0, 1, ... PHONGCL_LANES - 1. */
static inline uintv lane_numbers(void) {
#if PHONGCL_LANES == 1
  return 0u;
#else
  const uint numbers[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  return PHONGCL_XCAT(vload, PHONGCL_LANES)(0, numbers);
#endif
}

/* A pixel's rotation of the lattice, as two 32-bit fractions. */
typedef struct {
  uintv u, v;
} LatticeShift;

/* The shift for the lanes' pixels (`first_pixel` + lane) and a stream number (one per light, so
 * that two lights' rays are not aligned with each other). */
static inline LatticeShift lattice_shift(uint first_pixel, uint stream) {
  const uintv pixel = (uintv)first_pixel + lane_numbers();
  LatticeShift shift;
  shift.u = hash_uint(pixel ^ hash_uint((uintv)stream));
  shift.v = hash_uint(shift.u ^ 0x9e3779b9u);
  return shift;
}

/* A 32-bit fraction as a real in (0, 1): its top 24 bits and half of the last one's step. */
static inline realv fraction_of(uintv bits) {
  return TO_REALV(AS_INTV(bits >> 8)) * (real)0x1p-24 + (real)0x1p-25;
}

/* Point k of the shifted lattice. */
static inline void lattice_point(uint k, LatticeShift shift, realv* u, realv* v) {
  *u = fraction_of(shift.u + k * R2_STEP_U);
  *v = fraction_of(shift.v + k * R2_STEP_V);
}

#endif
