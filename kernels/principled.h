/* Cycles' Principled BSDF, version 1 (Blender 2.8 to 3.6, distribution GGX), under one light from
 * direction l: specular model 4 (specular.h numbers the others). Every formula, with the Cycles
 * file and function it matches, is in docs/shading.md "Principled". As the other lobes, the
 * responses are BRDF * pi * n.l (the Lambert 1/pi is folded into Li): the diffuse one is a factor
 * kd multiplies (kd = base colour * (1 - metallic), the host packs it), the specular one a colour
 * with the Fresnel's tint in it (ks is 1 for these lanes at the end). */
#ifndef PHONGCL_PRINCIPLED_H
#define PHONGCL_PRINCIPLED_H

#include "features.h"
#include "phong_math.h"

#define PRINCIPLED_MODEL 4

/* A lane's Principled parameters as the lights need them (read once per pixel). */
typedef struct {
  vec3 specular_color; /* cspec0: the specular colour at normal incidence (the host mixes it) */
  realv roughness;     /* the node's roughness: Burley's retro-reflection weight */
  realv alpha_sq;      /* GGX's alpha^2, alpha = roughness^2 */
  realv ior;           /* the index the Fresnel remaps from: 2 / (1 - sqrt(0.08 specular)) - 1 */
  realv f0;            /* that index's Fresnel at normal incidence */
} PrincipledSurface;

/* A light's response: kd multiplies `diffuse`, `specular` is already coloured. */
typedef struct {
  realv diffuse;
  vec3 specular;
} PrincipledResponse;

/* (1 - c)^5 with 1 - c clamped to [0, 1]: Burley's (Schlick's) weight. */
static inline realv schlick_weight(realv c) {
  const realv m = clamp(1 - c, (real)0, (real)1);
  const realv m2 = m * m;
  return m2 * m2 * m;
}

/* The unpolarised Fresnel reflectance of a dielectric of relative index `eta` at cosine c (Walter
 * et al. 2007, eq. 22); 1 under total internal reflection. */
static inline realv dielectric_fresnel(realv c, realv eta) {
  const realv g_sq = eta * eta - 1 + c * c;
  const realv g = sqrt(max(g_sq, (real)0));
  const realv a = (g - c) / (g + c);
  const realv b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return SELECT(g_sq > 0, (real)0.5 * a * a * (1 + b * b), 1);
}

/* Smith's masking for GGX at cosine c > 0, 2 / (1 + sqrt(1 + alpha^2 tan^2)), times c / c so that
 * grazing angles divide by nothing small: 2c / (c + sqrt(c^2 + alpha^2 (1 - c^2))). Its 2 is left
 * to principled_response. */
static inline realv half_smith_masking(realv c, realv alpha_sq) {
  return c / (c + sqrt(fma(alpha_sq, 1 - c * c, c * c)));
}

/* Burley's diffuse as Cycles 3.x writes it (Lambert's part and the retro-reflection apart), over
 * its 1/pi: (1 - FV/2)(1 - FL/2) + RR (FL + FV + FL FV (RR - 1)), RR = roughness (1 + l.v). */
static inline realv burley_factor(realv roughness, realv n_dot_l, realv n_dot_v, realv l_dot_v) {
  const realv fl = schlick_weight(n_dot_l), fv = schlick_weight(n_dot_v);
  const realv rr = roughness * (1 + l_dot_v);
  return (1 - (real)0.5 * fv) * (1 - (real)0.5 * fl) + rr * (fl + fv + fl * fv * (rr - 1));
}

/* v1's Fresnel is the dielectric's at l.h remapped from [f0, 1] to [cspec0, 1]: the specular colour
 * is cspec0 (1 - fh) + fh with this fh. f0 = 1 (index 0: the record of a lane of another model) takes
 * no Fresnel: its light is 0 there, and 0 * NaN would not be. */
static inline realv fresnel_blend(PrincipledSurface m, realv l_dot_h) {
  return SELECT(m.f0 < 1, (dielectric_fresnel(l_dot_h, m.ior) - m.f0) / (1 - m.f0), 0);
}

/* The diffuse and specular responses to a light from unit l, for unit n and v. */
static inline PrincipledResponse principled_response(PrincipledSurface m, vec3 n, vec3 v, vec3 l) {
  const realv n_dot_l = dot3(n, l), n_dot_v = dot3(n, v), l_dot_v = dot3(l, v);
  PrincipledResponse response;
  response.diffuse = SELECT(n_dot_l > 0, n_dot_l * burley_factor(m.roughness, n_dot_l, n_dot_v, l_dot_v), 0);
  /* GGX: pi D G / (4 n.v) with the n.l of L_o cancelled, D = alpha^2 / (pi (c^2 (alpha^2 - 1) + 1)^2),
   * c = n.h, G = G1(n.v) G1(n.l) separable. 0 where either side faces away, and for alpha^2 <= 1e-7 (a
   * mirror: no highlight from a point). */
  const vec3 s = add3(l, v);
  const realv inverse_s = rsqrt(max(dot3(s, s), (real)1e-30f));
  const realv n_dot_h = dot3(n, s) * inverse_s, l_dot_h = dot3(l, s) * inverse_s;
  /* c^2 (alpha^2 - 1) + 1 = sin^2 + c^2 alpha^2, sin^2 = |n x h|^2: near the peak 1 - c^2 would cancel
   * to float's rounding of c, which at alpha^2 = 1e-4 is 1e-3 of D. */
  const vec3 n_cross_s = cross3(n, s);
  const realv sin_sq = dot3(n_cross_s, n_cross_s) * (inverse_s * inverse_s);
  const realv d_root = fma(n_dot_h * n_dot_h, m.alpha_sq, sin_sq);
  const realv masking = half_smith_masking(n_dot_v, m.alpha_sq) * half_smith_masking(n_dot_l, m.alpha_sq);
  const realv lobe = m.alpha_sq * masking / (n_dot_v * d_root * d_root);
  const realv lit = SELECT(n_dot_l > 0 && n_dot_v > 0 && m.alpha_sq > (real)1e-7f, lobe, 0);
  const realv fh = fresnel_blend(m, l_dot_h);
  const realv tint = lit * (1 - fh), white = lit * fh;
  response.specular = make_vec3(fma(tint, m.specular_color.x, white), fma(tint, m.specular_color.y, white),
                                fma(tint, m.specular_color.z, white));
  return response;
}

#endif
