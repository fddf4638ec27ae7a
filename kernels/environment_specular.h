/* The environment light's specular (docs/environment.md "Specular"): each material's lobe convolved
 * with the map by the host, once per map and lobe (host/environment/prefiltered_map.h), read here at
 * the reflected direction r = 2(n.v)n - v. The Phong family's lobes are functions of r.w (Blinn's at
 * normal incidence), so a map per lobe is their exact convolution up to the grid: it holds the
 * lobe-weighted mean radiance, which the lobe's integral (`amplitude`) turns into its light, times n.r
 * for the normalised lobes (their n.l is n.r r.w plus a part odd about r, which the mean leaves out).
 * Principled lanes take Karis' split sum: the map prefiltered with GGX under n = v = r, times the
 * BRDF's white-world albedo: version 1's split by its Fresnel, cspec0 A + B (environment_brdf.h),
 * version 2's from Cycles' own tables (principled_v2_specular_albedo). The map holds
 * the sky without its suns, which come as directional lights and take their specular through
 * surface_light() as any light does. */
#ifndef PHONGCL_ENVIRONMENT_SPECULAR_H
#define PHONGCL_ENVIRONMENT_SPECULAR_H

#include "environment.h"
#include "environment_brdf.h"
#include "layout.h"

/* A and B of the BRDF table, bilinear in (n.v, roughness). */
static inline void environment_brdf_lookup(real n_dot_v, real roughness, real* scale, real* bias) {
  const int last = ENVIRONMENT_BRDF_SIZE - 1;
  const real fi = clamp(n_dot_v, (real)0, (real)1) * last, fj = clamp(roughness, (real)0, (real)1) * last;
  const int i = min((int)fi, last - 1), j = min((int)fj, last - 1);
  const real wi = fi - i, wj = fj - j;
  __constant const float* row0 = environment_brdf + 2 * (i * ENVIRONMENT_BRDF_SIZE + j);
  __constant const float* row1 = row0 + 2 * ENVIRONMENT_BRDF_SIZE;
  for (int k = 0; k < 2; ++k) {
    const real near = row0[k] + wj * (row0[2 + k] - row0[k]), far = row1[k] + wj * (row1[2 + k] - row1[k]);
    const real value = near + wi * (far - near);
    if (k == 0) *scale = value;
    else *bias = value;
  }
}

/* A version 1 Principled lane's specular albedo under a white world, cspec0 A + B. */
static inline vec3 principled_v1_specular_albedo(realv n_dot_v, realv roughness, vec3 specular_color) {
  real cosines[PHONGCL_LANES], roughnesses[PHONGCL_LANES], scales[PHONGCL_LANES], biases[PHONGCL_LANES];
  VSTORE(n_dot_v, 0, cosines);
  VSTORE(roughness, 0, roughnesses);
  for (int k = 0; k < PHONGCL_LANES; ++k) environment_brdf_lookup(cosines[k], roughnesses[k], &scales[k], &biases[k]);
  const realv scale = VLOAD(0, scales), bias = VLOAD(0, biases);
  return make_vec3(fma(scale, specular_color.x, bias), fma(scale, specular_color.y, bias), fma(scale, specular_color.z, bias));
}

/* One lane's specular light: its material's prefiltered radiance at r (the map's frame) times its
 * lobe's factor and `visible`, and a split sum's by the lane's `albedo`. */
static inline void environment_lane_specular(UNIFORM_SPACE const EnvironmentLobe* lobe, UNIFORM_SPACE const float* texels,
                                             real rx, real ry, real rz, real n_dot_r, real n_dot_v, const real* albedo,
                                             real visible, real* rgb) {
  equirect_lookup(texels + lobe->offset, lobe->width, lobe->height, rx, ry, rz, rgb);
  real factor = lobe->amplitude * (lobe->takes_cosine ? fmax(n_dot_r, (real)0) : (real)1);
  if (lobe->half_vector) factor *= n_dot_v;
  factor *= visible;
  for (int c = 0; c < 3; ++c) rgb[c] *= lobe->split_sum ? factor * albedo[c] : factor;
}

/* The specular light of each lane's material from the environment, scaled, times `visible` (its
 * lobe's sky-weighted free share, environment_specular_visibility; 1 without visibility): 0 in background
 * lanes and where the eye is behind the surface. `albedo` is the Principled lanes' white-world
 * specular albedo (read only where a lobe is a split sum). */
static inline vec3 environment_specular(UNIFORM_SPACE const EnvironmentRecord* environment, UNIFORM_SPACE const float* texels,
                                        UNIFORM_SPACE const EnvironmentLobe* lobes, intv material, vec3 n, vec3 v,
                                        vec3 albedo, realv visible) {
  const realv n_dot_v = dot3(n, v);
  const vec3 r = sub3(scale3(n, 2 * n_dot_v), v);
  UNIFORM_SPACE const float* m = environment->to_map;
  const realv x = m[0] * r.x + m[1] * r.y + m[2] * r.z;
  const realv y = m[4] * r.x + m[5] * r.y + m[6] * r.z;
  const realv z = m[8] * r.x + m[9] * r.y + m[10] * r.z;
  const realv n_dot_r = dot3(n, r);
  const real scale = environment->scale;
#if PHONGCL_LANES == 1
  const real white[3] = {albedo.x, albedo.y, albedo.z};
  real rgb[3] = {0, 0, 0};
  if (material != PHONGCL_BACKGROUND && n_dot_v > 0)
    environment_lane_specular(&lobes[material], texels, x, y, z, n_dot_r, n_dot_v, white, visible, rgb);
  return make_vec3(rgb[0] * scale, rgb[1] * scale, rgb[2] * scale);
#else
  real xs[PHONGCL_LANES], ys[PHONGCL_LANES], zs[PHONGCL_LANES], nr[PHONGCL_LANES], nv[PHONGCL_LANES];
  real cr[PHONGCL_LANES], cg[PHONGCL_LANES], cb[PHONGCL_LANES], seen[PHONGCL_LANES];
  real r_out[PHONGCL_LANES], g_out[PHONGCL_LANES], b_out[PHONGCL_LANES];
  int materials[PHONGCL_LANES];
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(x, 0, xs);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(y, 0, ys);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(z, 0, zs);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(n_dot_r, 0, nr);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(n_dot_v, 0, nv);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(albedo.x, 0, cr);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(albedo.y, 0, cg);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(albedo.z, 0, cb);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(visible, 0, seen);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(material, 0, materials);
  for (int k = 0; k < PHONGCL_LANES; ++k) {
    const real white[3] = {cr[k], cg[k], cb[k]};
    real rgb[3] = {0, 0, 0};
    if (materials[k] != PHONGCL_BACKGROUND && nv[k] > 0)
      environment_lane_specular(&lobes[materials[k]], texels, xs[k], ys[k], zs[k], nr[k], nv[k], white, seen[k], rgb);
    r_out[k] = rgb[0] * scale;
    g_out[k] = rgb[1] * scale;
    b_out[k] = rgb[2] * scale;
  }
  return make_vec3(PHONGCL_XCAT(vload, PHONGCL_LANES)(0, r_out), PHONGCL_XCAT(vload, PHONGCL_LANES)(0, g_out),
                   PHONGCL_XCAT(vload, PHONGCL_LANES)(0, b_out));
#endif
}

/* The share of each lane's lobe light that reaches it: `rays` directions spread about r = 2(n.v)n - v
 * by its lobe's width (EnvironmentLobe.spread, s: at angle s sqrt(-2 ln(1 - a)) from r, a Gaussian's
 * radius, over the shifted R2 lattice), each weighted by the sky's radiance there (the map without its
 * suns, summed over R, G and B). The prefiltered map holds the lobe's mean over every direction, so the
 * share is (the sum over the free directions above the surface) / (the sum over all of them), the
 * light the surface's horizon and the geometry leave. A split-sum lobe's table holds the horizon's cut
 * already, so its share is over the rays above the surface only (their count, not every ray's, over
 * the same): the mean over the free directions above the surface over the mean over all. Weighting by
 * the sky matters where the lobe crosses the horizon: on a glancing ground it lifts the lobe's mean to
 * the bright sky above (the map's dark ground below the surface left out), and a ray blocked by the
 * ground takes away the dark ground's radiance, not the lobe's mean (the plain free fraction left
 * Cycles' glossy median 5.8% off under check 67's HDRI, the ground 8% and the metal 7% dark;
 * docs/environment.md). A uniform world looks nothing up. The rays are directional lights' (to
 * infinity). In the lanes of `pending` (a split sum's where some ray is above the surface); 1 elsewhere.
 * Lagarde's specular occlusion from the diffuse light's visible fraction was measured first: it takes
 * the ground away from a face whose reflection looks up, and leaves the sky to one whose reflection
 * looks down into the ground. */
static inline SHADOW_INLINE realv environment_specular_visibility(const ShadowInputs* shadows,
                                                                  UNIFORM_SPACE const EnvironmentRecord* environment,
                                                                  UNIFORM_SPACE const float* texels,
                                                                  UNIFORM_SPACE const EnvironmentLobe* lobes, intv material,
                                                                  vec3 p, vec3 n, vec3 v, uint rays, LatticeShift shift,
                                                                  intv pending) {
  if (!any_lane(pending) || rays == 0) return 1;
  ShadowInputs traced = *shadows;
  traced.tiles = 0;
  UNIFORM_SPACE const float* sky = texels + environment->sky_offset;
  const bool uniform_sky = environment->sky_width * environment->sky_height == 1;
  const vec3 r = sub3(scale3(n, 2 * dot3(n, v)), v);
#if PHONGCL_LANES == 1
  const realv spread = material != PHONGCL_BACKGROUND ? lobes[material].spread : 0;
  const realv split_sum = material != PHONGCL_BACKGROUND && lobes[material].split_sum ? 1 : 0;
#else
  int materials[PHONGCL_LANES];
  real spreads[PHONGCL_LANES], split_sums[PHONGCL_LANES];
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(material, 0, materials);
  for (int k = 0; k < PHONGCL_LANES; ++k) {
    const bool lobe = materials[k] != PHONGCL_BACKGROUND;
    spreads[k] = lobe ? lobes[materials[k]].spread : 0;
    split_sums[k] = lobe && lobes[materials[k]].split_sum ? 1 : 0;
  }
  const realv spread = PHONGCL_XCAT(vload, PHONGCL_LANES)(0, spreads);
  const realv split_sum = PHONGCL_XCAT(vload, PHONGCL_LANES)(0, split_sums);
#endif
  vec3 a, b;
  orthonormal_basis(r, &a, &b);
  realv free = 0, seen = 0, all = 0;
  for (uint k = 0; k < rays; ++k) {
    realv s, t;
    lattice_point(k, shift, &s, &t);
    const realv angle = fmin(spread * sqrt(-2 * log(fmax(1 - s, (realv)1e-6f))), (realv)ENVIRONMENT_PI);
    const realv around = (real)(2 * ENVIRONMENT_PI) * t;
    const realv sine = sin(angle);
    const vec3 d = add3(add3(scale3(a, sine * cos(around)), scale3(b, sine * sin(around))), scale3(r, cos(angle)));
    const intv above = LANE_MASK(dot3(n, d) > 0);
    const intv blocked = light_blocked(&traced, p, n, d, 1, SCREEN_SHADOWS, 0, pending & above);
    realv weight = 1;
    if (!uniform_sky) {
      const vec3 radiance = environment_grid(environment, sky, environment->sky_width, environment->sky_height, d);
      weight = radiance.x + radiance.y + radiance.z;
    }
    free += SELECT(TO_REALV(above) != 0 && TO_REALV(blocked) == 0, weight, 0);
    seen += SELECT(TO_REALV(above) != 0, 1, 0);
    all += weight;
  }
  /* free / all, times rays / seen for a split sum (with a uniform sky free / seen, or free / rays). */
  const realv counted = SELECT(split_sum != 0, fmax(seen, (realv)1), (realv)rays);
  const realv share = free * (real)rays / (counted * fmax(all, (realv)1e-30f));
  return SELECT(TO_REALV(pending) != 0 && all > 0 && (seen > 0 || split_sum == 0), share, 1);
}

#endif
