/* The specular lobe: Phong's max(0, v.r)^q with r = 2(n.l)n - l, for l = toward * inverse (inverse
 * = 1 / |toward|) and n_dot = n.toward. */
#ifndef PHONGCL_SPECULAR_H
#define PHONGCL_SPECULAR_H

#include "phong_math.h"

static inline realv phong_specular(vec3 n, vec3 v, vec3 toward, realv inverse, realv n_dot, realv shininess) {
  /* r = 2(n.l)n - l = -inverse * w, w = toward - 2(n.toward)n with one rounding per component.
   * Near the highlight peak v - r = v + inverse * w has one rounding too (fma), so w's rounding is
   * all the error in 1 - v.r, which the specular power multiplies by q. */
  const realv two_n_dot = 2 * n_dot;
  const vec3 w = make_vec3(fma(-two_n_dot, n.x, toward.x), fma(-two_n_dot, n.y, toward.y), fma(-two_n_dot, n.z, toward.z));
  const vec3 v_minus_r = make_vec3(fma(inverse, w.x, v.x), fma(inverse, w.y, v.y), fma(inverse, w.z, v.z));
  const realv cos_vr = -inverse * dot3(v, w);
  return specular_power(cos_vr, (real)0.5 * dot3(v_minus_r, v_minus_r), shininess);
}

#endif
