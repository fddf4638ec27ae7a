/* The specular lobes (docs/shading.md "Specular models"), numbered as the host's SpecularModel:
 *   0 phong                   max(0, v.r)^q, r = 2(n.l)n - l        (the default)
 *   1 phong-normalized        (q+2)/2 max(0, v.r)^q n.l            (Lafortune and Willems 1994)
 *   2 blinn-phong             max(0, n.h)^q, h = normalize(l + v)
 *   3 blinn-phong-normalized  (q+8)/8 max(0, n.h)^q n.l            (Real-Time Rendering's approximation)
 * A normalised lobe is a BRDF times pi (the Lambert 1/pi is folded into Li), so it takes the cosine
 * n.l as the diffuse term does; the classic ones keep the highlight without it. Here the lobes'
 * cosines for l = toward * inverse (inverse = 1 / |toward|) and n_dot = n.toward; phong.cl raises
 * them to the power q, multiplies by n.l per light and by the factor (q+c)/c once per pixel, where
 * the normalised ones need them. */
#ifndef PHONGCL_SPECULAR_H
#define PHONGCL_SPECULAR_H

#include "features.h"
#include "phong_math.h"

/* Phong's v.r and 1 - v.r, for max(0, v.r)^q. */
static inline LobeCosine phong_cosine(vec3 n, vec3 v, vec3 toward, realv inverse, realv n_dot) {
  /* r = 2(n.l)n - l = -inverse * w, w = toward - 2(n.toward)n with one rounding per component.
   * Near the highlight peak v - r = v + inverse * w has one rounding too (fma), so w's rounding is
   * all the error in 1 - v.r, which the specular power multiplies by q. */
  const realv two_n_dot = 2 * n_dot;
  const vec3 w = make_vec3(fma(-two_n_dot, n.x, toward.x), fma(-two_n_dot, n.y, toward.y), fma(-two_n_dot, n.z, toward.z));
  const vec3 v_minus_r = make_vec3(fma(inverse, w.x, v.x), fma(inverse, w.y, v.y), fma(inverse, w.z, v.z));
  const LobeCosine lobe = {-inverse * dot3(v, w), (real)0.5 * dot3(v_minus_r, v_minus_r)};
  return lobe;
}

/* Blinn's n.h and 1 - n.h, for max(0, n.h)^q. s = l + v = toward * inverse + v with one rounding
 * per component (fma), h = s / |s|, and near the peak n - h = n - s / |s| with one more (fma):
 * 1 - n.h = |n - h|^2 / 2 without cancellation. A length error d in n or h scales it by 1 + d
 * (plus d^2 / 2), so rsqrt's rounding is a relative error, not one q multiplies; s's own rounding is
 * all that q amplifies, as w's is in phong_cosine. s = 0 (v = -l, the eye behind the surface) has
 * no half vector: n.h is taken as 0. */
static inline LobeCosine blinn_cosine(vec3 n, vec3 v, vec3 toward, realv inverse) {
  const vec3 s = make_vec3(fma(toward.x, inverse, v.x), fma(toward.y, inverse, v.y), fma(toward.z, inverse, v.z));
  const realv s_length_sq = dot3(s, s);
  const realv inverse_s = SELECT(s_length_sq > 0, rsqrt(s_length_sq), 0);
  const vec3 n_minus_h = make_vec3(fma(-inverse_s, s.x, n.x), fma(-inverse_s, s.y, n.y), fma(-inverse_s, s.z, n.z));
  const LobeCosine lobe = {inverse_s * dot3(n, s), (real)0.5 * dot3(n_minus_h, n_minus_h)};
  return lobe;
}

/* The cosine of each lane's model (`model`, its number, read only where lanes may differ): the
 * lobe is specular_power() of it, without the normalised models' n.l and factor. */
static inline LobeCosine lobe_cosine(vec3 n, vec3 v, vec3 toward, realv inverse, realv n_dot, realv model) {
  if (!HALF_VECTOR_LOBES) return phong_cosine(n, v, toward, inverse, n_dot);
  if (!REFLECTION_LOBES) return blinn_cosine(n, v, toward, inverse);
  const LobeCosine blinn = blinn_cosine(n, v, toward, inverse), phong = phong_cosine(n, v, toward, inverse, n_dot);
  const LobeCosine lobe = {SELECT(model >= 2, blinn.cosine, phong.cosine),
                           SELECT(model >= 2, blinn.one_minus_cosine, phong.one_minus_cosine)};
  return lobe;
}

/* 1 where each lane's model is normalised and takes the cosine n.l, else 0. */
static inline realv normalized_model(realv model) {
  if (!MIXED_SPECULAR_MODELS) return NORMALIZED_LOBES ? 1 : 0;
  return SELECT(model == 1 || model == 3, 1, 0);
}

/* The normalised models' factor (q+2)/2 or (q+8)/8, 1 for the others: 1 + q / c in one rounding. */
static inline realv specular_normalization(realv shininess, realv model) {
  const realv inverse_c = !MIXED_SPECULAR_MODELS ? ((SPECULAR_MODELS & 2) ? (real)0.5 : (real)0.125)
                                                 : SELECT(model == 1, 0.5, SELECT(model == 3, 0.125, 0));
  return fma(shininess, inverse_c, 1);
}

#endif
