/* Cycles' Principled BSDF under one light from direction l: version 1 (Blender 2.8 to 3.6, distribution
 * GGX) is specular model 4, version 2 (Blender 4.0 on, distribution multiscatter GGX) model 5
 * (specular.h numbers the others). Every formula, with the Cycles
 * file and function it matches, is in docs/shading.md "Principled". As the other lobes, the
 * responses are BRDF * pi * n.l (the Lambert 1/pi is folded into Li): the diffuse one is a factor
 * kd multiplies (kd = base colour * (1 - metallic), the host packs it), the specular one a colour
 * with the Fresnel's tint in it (ks is 1 for these lanes at the end). */
#ifndef PHONGCL_PRINCIPLED_H
#define PHONGCL_PRINCIPLED_H

#include "features.h"
#include "oren_nayar.h"
#include "phong_math.h"
#include "principled_tables.h"

#define PRINCIPLED_MODEL 4
#define PRINCIPLED_V2_MODEL 5

/* A lane's Principled parameters as the lights need them (read once per pixel). */
typedef struct {
  vec3 specular_color; /* cspec0: the specular colour at normal incidence (the host mixes it) */
  realv roughness;     /* the node's roughness: Burley's retro-reflection weight */
  realv alpha_sq;      /* GGX's alpha^2, alpha = roughness^2 */
  realv ior;           /* the index the Fresnel remaps from: 2 / (1 - sqrt(0.08 specular)) - 1 */
  realv f0;            /* that index's Fresnel at normal incidence */
} PrincipledSurface;

/* A light's response: kd multiplies `diffuse`, `specular` is already coloured. With OREN_NAYAR a
 * version 2 lane's multiple scattering is apart, `diffuse_multiple` times the surface's per-channel M
 * (oren_nayar.h). */
typedef struct {
  realv diffuse, diffuse_multiple;
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

/* GGX's denominator root c^2 (alpha^2 - 1) + 1 = sin^2 + c^2 alpha^2 at c = n.h, h halfway between
 * unit l and v, and l.h. sin^2 = |n x h|^2: near the peak 1 - c^2 would cancel to float's rounding of
 * c, which at alpha^2 = 1e-4 is 1e-3 of D. */
static inline realv ggx_denominator_root(vec3 n, vec3 v, vec3 l, realv alpha_sq, realv* l_dot_h) {
  const vec3 s = add3(l, v);
  const realv inverse_s = rsqrt(max(dot3(s, s), (real)1e-30f));
  const realv n_dot_h = dot3(n, s) * inverse_s;
  *l_dot_h = dot3(l, s) * inverse_s;
  const vec3 n_cross_s = cross3(n, s);
  const realv sin_sq = dot3(n_cross_s, n_cross_s) * (inverse_s * inverse_s);
  return fma(n_dot_h * n_dot_h, alpha_sq, sin_sq);
}

/* The diffuse and specular responses to a light from unit l, for unit n and v. */
static inline PrincipledResponse principled_response(PrincipledSurface m, vec3 n, vec3 v, vec3 l) {
  const realv n_dot_l = dot3(n, l), n_dot_v = dot3(n, v), l_dot_v = dot3(l, v);
  PrincipledResponse response;
  response.diffuse = SELECT(n_dot_l > 0, n_dot_l * burley_factor(m.roughness, n_dot_l, n_dot_v, l_dot_v), 0);
  /* GGX: pi D G / (4 n.v) with the n.l of L_o cancelled, D = alpha^2 / (pi (c^2 (alpha^2 - 1) + 1)^2),
   * c = n.h, G = G1(n.v) G1(n.l) separable. 0 where either side faces away, and for alpha^2 <= 1e-7 (a
   * mirror: no highlight from a point). */
  realv l_dot_h;
  const realv d_root = ggx_denominator_root(n, v, l, m.alpha_sq, &l_dot_h);
  const realv masking = half_smith_masking(n_dot_v, m.alpha_sq) * half_smith_masking(n_dot_l, m.alpha_sq);
  const realv lobe = m.alpha_sq * masking / (n_dot_v * d_root * d_root);
  const realv lit = SELECT(n_dot_l > 0 && n_dot_v > 0 && m.alpha_sq > (real)1e-7f, lobe, 0);
  const realv fh = fresnel_blend(m, l_dot_h);
  const realv tint = lit * (1 - fh), white = lit * fh;
  response.specular = make_vec3(fma(tint, m.specular_color.x, white), fma(tint, m.specular_color.y, white),
                                fma(tint, m.specular_color.z, white));
  return response;
}

/* ---- Version 2 (Blender 4.0 on): Cycles' svm/closure.h, CLOSURE_BSDF_PRINCIPLED_ID, without coat,
 * sheen, transmission, subsurface, thin film and anisotropy. A metal lobe (F82-tint Fresnel) of weight
 * metallic, over it a dielectric lobe (the real Fresnel remapped to [f0 tint, 1]) of weight 1 - metallic,
 * both GGX with height-correlated masking and multiscatter energy compensation, and Lambert's diffuse
 * beneath, attenuated by the dielectric layer's albedo. ---- */

/* A lane's version 2 parameters, read once per pixel (principled_v2_surface). */
typedef struct {
  vec3 metal_f0, metal_b;      /* F82 tint: the base colour (at most 1) and its B term */
  vec3 metal_scale;            /* metallic times the energy compensation, per channel */
  vec3 dielectric_f0;          /* F0(ior) 2 specular_ior_level times the specular tint, saturated */
  vec3 dielectric_scale;       /* 1 - metallic times the energy compensation (0 without the layer) */
  realv alpha_sq;              /* GGX's alpha^2, alpha = roughness^2 */
  realv ior, ior_f0;           /* the dielectric's index (after the level) and its F0 */
  realv diffuse_scale;         /* what the dielectric layer leaves the diffuse beneath, at this view */
  OrenNayarSurface rough;      /* with OREN_NAYAR, the diffuse's Oren-Nayar (sigma 0: Lambert's) */
} PrincipledV2Surface;

/* Cycles' lookup_table_read: linear between the two entries about x in [0, 1] of a row of `size`. */
static inline real table_row(__constant const float* row, real x, int size) {
  const real at = clamp(x, (real)0, (real)1) * (size - 1);
  const int index = min((int)at, size - 1), next = min(index + 1, size - 1);
  const real t = at - index;
  return fma(t, (real)row[next], (1 - t) * (real)row[index]);
}

/* lookup_table_read_2D: rows of nx along y in [0, 1], linear between the two rows about y. */
static inline real table_plane(__constant const float* plane, real x, real y, int nx, int ny) {
  const real at = clamp(y, (real)0, (real)1) * (ny - 1);
  const int index = min((int)at, ny - 1), next = min(index + 1, ny - 1);
  const real t = at - index;
  return fma(t, table_row(plane + next * nx, x, nx), (1 - t) * table_row(plane + index * nx, x, nx));
}

/* GGX's tables at each lane's roughness, view cosine mu and index axis z (principled_tables.h): the
 * directional albedo E, its average E_avg, and the dielectric Fresnel's mean interpolation factor s
 * (lookup_table_read_3D: linear between the two planes about z). */
static inline void ggx_table_lanes(realv roughness, realv mu, realv z, realv* albedo, realv* average,
                                   realv* interpolation) {
  real r[PHONGCL_LANES], m[PHONGCL_LANES], zs[PHONGCL_LANES], e[PHONGCL_LANES], a[PHONGCL_LANES], s[PHONGCL_LANES];
  VSTORE(roughness, 0, r);
  VSTORE(mu, 0, m);
  VSTORE(z, 0, zs);
  const int n = GGX_INTERPOLATION_SIZE;
  for (int k = 0; k < PHONGCL_LANES; ++k) {
    e[k] = table_plane(ggx_albedo_table, r[k], m[k], GGX_ALBEDO_SIZE, GGX_ALBEDO_SIZE);
    a[k] = table_row(ggx_average_albedo_table, r[k], GGX_ALBEDO_SIZE);
    const real at = clamp(zs[k], (real)0, (real)1) * (n - 1);
    const int index = min((int)at, n - 1), next = min(index + 1, n - 1);
    const real t = at - index;
    s[k] = fma(t, table_plane(ggx_fresnel_interpolation_table + next * n * n, r[k], m[k], n, n),
               (1 - t) * table_plane(ggx_fresnel_interpolation_table + index * n * n, r[k], m[k], n, n));
  }
  *albedo = VLOAD(0, e);
  *average = VLOAD(0, a);
  *interpolation = VLOAD(0, s);
}

/* microfacet_ggx_preserve_energy's factor on a lobe of mean single-scattering Fresnel fss:
 * 1 + Fms (1 - E) / E, Fms = fss E_avg / (1 - fss (1 - E_avg)) (Kulla and Conty 2017). */
static inline realv ggx_energy_compensation(realv fss, realv missing, realv average) {
  return fma(fss * average / (1 - fss * (1 - average)), missing, 1);
}

/* The F82-tint Fresnel at cosine c (Kutz et al., "Novel aspects of the Adobe Standard Material"):
 * Schlick's mix(f0, 1, (1 - c)^5) less b c (1 - c)^6, saturated (bsdf_util.h, fresnel_f82). */
static inline realv f82_tint_fresnel(realv c, realv f0, realv b) {
  const realv m = clamp(1 - c, (real)0, (real)1);
  const realv m5 = m * m * m * m * m;
  return clamp(fma(1 - f0, m5, f0) - b * c * m5 * m, (real)0, (real)1);
}

/* The dielectric's Fresnel at cosine c remapped from [F0(ior), 1] to [f0, 1] (microfacet_fresnel, the
 * generalised Schlick's case exponent < 0). t is the remap's factor, shared by the three channels. */
static inline realv remapped_fresnel(realv t, realv f0) { return fma(1 - f0, t, f0); }

/* A lane's version 2 parameters at view cosine mu: the record's fields, E, E_avg and s from the
 * tables, the lobes' energy compensation, the diffuse's share under the dielectric layer
 * (closure_layering_weight: 1 - the largest channel of the layer's albedo, its weight divided out)
 * and with OREN_NAYAR its Oren-Nayar of the base colour (metal_f0, saturated). */
static inline PrincipledV2Surface principled_v2_surface(vec3 metal_f0, vec3 metal_b, realv metallic, vec3 dielectric_f0,
                                                        realv dielectric_layer, realv roughness, realv ior,
                                                        realv fresnel_average, realv diffuse_roughness, realv mu) {
  PrincipledV2Surface m;
  m.metal_f0 = metal_f0, m.metal_b = metal_b, m.dielectric_f0 = dielectric_f0, m.ior = ior;
  m.alpha_sq = roughness * roughness * roughness * roughness;
  const realv ratio = (ior - 1) / (ior + 1);
  m.ior_f0 = ratio * ratio;
  realv albedo, average, interpolation;
  ggx_table_lanes(roughness, mu, sqrt(fabs(ratio)), &albedo, &average, &interpolation);
  const realv missing = (1 - albedo) / albedo;
  /* fresnel_f82_Fss: the F82 lobe's hemispherical mean, mix(f0, 1, 1/21) - b/126. */
  const realv per_21 = (real)1 / 21, per_126 = (real)1 / 126;
  m.metal_scale = make_vec3(
      metallic * ggx_energy_compensation(fma(1 - metal_f0.x, per_21, metal_f0.x) - metal_b.x * per_126, missing, average),
      metallic * ggx_energy_compensation(fma(1 - metal_f0.y, per_21, metal_f0.y) - metal_b.y * per_126, missing, average),
      metallic * ggx_energy_compensation(fma(1 - metal_f0.z, per_21, metal_f0.z) - metal_b.z * per_126, missing, average));
  const vec3 boost = make_vec3(ggx_energy_compensation(remapped_fresnel(fresnel_average, dielectric_f0.x), missing, average),
                               ggx_energy_compensation(remapped_fresnel(fresnel_average, dielectric_f0.y), missing, average),
                               ggx_energy_compensation(remapped_fresnel(fresnel_average, dielectric_f0.z), missing, average));
  const realv weight = (1 - metallic) * dielectric_layer;
  m.dielectric_scale = scale3(boost, weight);
  /* bsdf_microfacet_estimate_albedo: mix(f0, 1, s) times the compensation's darkening, boost / (1 + missing). */
  const realv darkening = 1 / (1 + missing);
  const realv layer_albedo = max(max(remapped_fresnel(interpolation, dielectric_f0.x) * boost.x,
                                     remapped_fresnel(interpolation, dielectric_f0.y) * boost.y),
                                 remapped_fresnel(interpolation, dielectric_f0.z) * boost.z) * darkening;
  m.diffuse_scale = SELECT(dielectric_layer > 0, clamp(1 - layer_albedo, (real)0, (real)1), 1);
  if (OREN_NAYAR) m.rough = oren_nayar_surface(diffuse_roughness, metal_f0, mu);
  return m;
}

/* Version 2's share of Lambert's light from unit l (an area light's centre): the dielectric layer's,
 * times with OREN_NAYAR the diffuse's response over Lambert's there (n.l at least 1e-4: a light
 * about the horizon takes its limit). */
static inline vec3 principled_v2_lambert_share(PrincipledV2Surface m, vec3 n, vec3 v, vec3 l) {
  if (!OREN_NAYAR) return make_vec3(m.diffuse_scale, m.diffuse_scale, m.diffuse_scale);
  const realv n_dot_l = max(dot3(n, l), (real)1e-4f);
  const realv single = oren_nayar_single(m.rough, n_dot_l, dot3(n, v), dot3(l, v)) / n_dot_l;
  const realv weight = OREN_NAYAR_G0 - oren_nayar_g(n_dot_l);
  return scale3(make_vec3(fma(m.rough.multiple.x, weight, single), fma(m.rough.multiple.y, weight, single),
                          fma(m.rough.multiple.z, weight, single)),
                m.diffuse_scale);
}

/* Version 2's share of the environment's Lambert light: the layer's, times with OREN_NAYAR the
 * diffuse's white-world response over Lambert's (exact for a uniform world). */
static inline vec3 principled_v2_sky_share(PrincipledV2Surface m) {
  if (!OREN_NAYAR) return make_vec3(m.diffuse_scale, m.diffuse_scale, m.diffuse_scale);
  return scale3(oren_nayar_white_sky(m.rough), m.diffuse_scale);
}

/* Version 2's specular albedo at view cosine mu under a white world, per channel, for the environment's
 * split sum: E times each lobe's mean Fresnel over the reflected light, the metal's from its F82
 * factors (principled_tables.h), the dielectric's Cycles' own estimate mix(f0, 1, s)
 * (bsdf_microfacet_estimate_albedo), each times its scale (with the energy compensation). */
static inline vec3 principled_v2_specular_albedo(PrincipledV2Surface m, realv mu) {
  const realv roughness = sqrt(sqrt(m.alpha_sq));
  realv albedo, average, interpolation;
  ggx_table_lanes(roughness, mu, sqrt(sqrt(m.ior_f0)), &albedo, &average, &interpolation);
  real r[PHONGCL_LANES], c[PHONGCL_LANES], schlick[PHONGCL_LANES], f82[PHONGCL_LANES];
  VSTORE(roughness, 0, r);
  VSTORE(mu, 0, c);
  for (int k = 0; k < PHONGCL_LANES; ++k) {
    schlick[k] = table_plane(ggx_schlick_factor_table, r[k], c[k], GGX_ALBEDO_SIZE, GGX_ALBEDO_SIZE);
    f82[k] = table_plane(ggx_f82_factor_table, r[k], c[k], GGX_ALBEDO_SIZE, GGX_ALBEDO_SIZE);
  }
  const realv s5 = VLOAD(0, schlick), s6 = VLOAD(0, f82);
  const vec3 metal = make_vec3(clamp(fma(1 - m.metal_f0.x, s5, m.metal_f0.x) - m.metal_b.x * s6, (real)0, (real)1),
                               clamp(fma(1 - m.metal_f0.y, s5, m.metal_f0.y) - m.metal_b.y * s6, (real)0, (real)1),
                               clamp(fma(1 - m.metal_f0.z, s5, m.metal_f0.z) - m.metal_b.z * s6, (real)0, (real)1));
  return scale3(make_vec3(fma(m.metal_scale.x, metal.x, m.dielectric_scale.x * remapped_fresnel(interpolation, m.dielectric_f0.x)),
                          fma(m.metal_scale.y, metal.y, m.dielectric_scale.y * remapped_fresnel(interpolation, m.dielectric_f0.y)),
                          fma(m.metal_scale.z, metal.z, m.dielectric_scale.z * remapped_fresnel(interpolation, m.dielectric_f0.z))),
                albedo);
}

/* Version 2's diffuse and specular responses to a light from unit l, for unit n and v. */
static inline PrincipledResponse principled_v2_response(PrincipledV2Surface m, vec3 n, vec3 v, vec3 l) {
  const realv n_dot_l = dot3(n, l), n_dot_v = dot3(n, v);
  PrincipledResponse response;
  if (OREN_NAYAR) {
    response.diffuse = m.diffuse_scale * oren_nayar_single(m.rough, n_dot_l, n_dot_v, dot3(l, v));
    response.diffuse_multiple = m.diffuse_scale * oren_nayar_multiple_weight(n_dot_l);
  } else {
    response.diffuse = SELECT(n_dot_l > 0, n_dot_l * m.diffuse_scale, 0);
  }
  realv l_dot_h;
  const realv d_root = ggx_denominator_root(n, v, l, m.alpha_sq, &l_dot_h);
  /* pi D G2 / (4 n.v), D = alpha^2 / (pi d_root^2), height-correlated G2 = 1 / (1 + Lambda_v + Lambda_l),
   * 1 + Lambda(c) = (1 + root(c) / c) / 2 with root(c) = sqrt(c^2 + alpha^2 (1 - c^2)). */
  const realv root_v = sqrt(fma(m.alpha_sq, 1 - n_dot_v * n_dot_v, n_dot_v * n_dot_v));
  const realv root_l = sqrt(fma(m.alpha_sq, 1 - n_dot_l * n_dot_l, n_dot_l * n_dot_l));
  const realv lobe = m.alpha_sq * n_dot_l / (2 * d_root * d_root * fma(root_v, n_dot_l, root_l * n_dot_v));
  /* BSDF_ROUGHNESS_SQ_THRESH: alpha^2 <= 2e-10 is a mirror (no highlight from a point). */
  const realv lit = SELECT(n_dot_l > 0 && n_dot_v > 0 && m.alpha_sq > (real)2e-10f, lobe, 0);
  /* ior_f0 = 1 is the record of a lane of another model (index 0): no Fresnel, and no 0 * NaN. */
  const realv t = SELECT(m.ior_f0 < 1,
                         clamp((dielectric_fresnel(l_dot_h, m.ior) - m.ior_f0) / (1 - m.ior_f0), (real)0, (real)1), 0);
  response.specular = make_vec3(
      lit * fma(m.metal_scale.x, f82_tint_fresnel(l_dot_h, m.metal_f0.x, m.metal_b.x),
                m.dielectric_scale.x * remapped_fresnel(t, m.dielectric_f0.x)),
      lit * fma(m.metal_scale.y, f82_tint_fresnel(l_dot_h, m.metal_f0.y, m.metal_b.y),
                m.dielectric_scale.y * remapped_fresnel(t, m.dielectric_f0.y)),
      lit * fma(m.metal_scale.z, f82_tint_fresnel(l_dot_h, m.metal_f0.z, m.metal_b.z),
                m.dielectric_scale.z * remapped_fresnel(t, m.dielectric_f0.z)));
  return response;
}

#endif
