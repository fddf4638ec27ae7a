/* Cycles' Oren-Nayar diffuse (closure/bsdf_oren_nayar.h, Blender 4.3 on), which version 2's Principled
 * BSDF takes where Diffuse Roughness sigma is above 0 (OREN_NAYAR): Fujii's improved model,
 * a + b t with b = sigma a, and OpenPBR's energy-preserving multiple scattering,
 * Ems (1 - E(n.v)) (1 - E(n.l)). docs/shading.md states every formula with its Cycles function.
 * Every 1 - E is written sigma a (G(0) - G(c)): E -> 1 as sigma -> 0, and the difference taken in
 * float would lose what the multiple scattering is made of. As the other lobes, the responses are
 * BRDF * pi * n.l over the closure's colour (Lambert's is n.l). */
#ifndef PHONGCL_OREN_NAYAR_H
#define PHONGCL_OREN_NAYAR_H

#include "phong_math.h"

#if PHONGCL_DOUBLE
#define OREN_NAYAR_PI M_PI
#else
#define OREN_NAYAR_PI M_PI_F
#endif
/* G(0) = pi/2 - 2/3, and G's mean over the hemisphere, 2 c G(c) dc over [0, 1]: (2 pi - 5.6) / 3. */
#define OREN_NAYAR_G0 ((real)OREN_NAYAR_PI / 2 - (real)2 / 3)
#define OREN_NAYAR_G_MEAN ((2 * (real)OREN_NAYAR_PI - (real)28 / 5) / 3)

/* A lane's Oren-Nayar parameters at its view cosine (bsdf_oren_nayar_param). */
typedef struct {
  realv single; /* pi a = pi / (pi + sigma G(0)): the single scattering's a over Lambert's 1/pi (1 at sigma 0) */
  realv sigma;  /* b / a */
  vec3 multiple; /* M: the multiple scattering's light is M (G(0) - G(n.l)) n.l, per channel */
  realv white_sky; /* the single scattering's albedo at this view, E(n.v) = a (pi + sigma G(n.v)) */
} OrenNayarSurface;

/* Fujii's G(c) = sin (theta - 2/3 - sin cos) + 2/3 tan (1 - sin^3) at cosine c in [0, 1], its last term
 * as 2/3 s c (1 + s + s^2) / (1 + s) (1 - s^3 = (1 - s)(1 + s + s^2), 1 - s = c^2 / (1 + s)): grazing c
 * then divides by nothing, where Cycles' bsdf_oren_nayar_G falls back to a Taylor series. */
static inline realv oren_nayar_g(realv c) {
  const realv s = sqrt(max(1 - c * c, (real)0));
  return s * (acos(c) - (real)2 / 3 - s * c) + (real)2 / 3 * s * c * (1 + s + s * s) / (1 + s);
}

/* A channel's M = albedo^2 Eavg / (1 - Eavg) (1 - E(n.v)) sigma a / (1 - albedo (1 - Eavg)): pi Ems (1 - E(n.v))
 * with 1 - E(n.l)'s sigma a taken in. `ratio` = Eavg / (1 - Eavg) (1 - E(n.v)), `missing` = 1 - Eavg. */
static inline realv oren_nayar_multiple(realv albedo, realv ratio, realv sigma_a, realv missing) {
  return albedo * albedo * ratio * sigma_a / (1 - albedo * missing);
}

/* bsdf_oren_nayar_param for roughness sigma in [0, 1], the closure colour's albedo (in [0, 1]) and view
 * cosine mu in [0, 1]. */
static inline OrenNayarSurface oren_nayar_surface(realv sigma, vec3 albedo, realv mu) {
  OrenNayarSurface m;
  const realv a = 1 / fma(sigma, OREN_NAYAR_G0, (real)OREN_NAYAR_PI);
  const realv g_v = oren_nayar_g(mu);
  m.single = (real)OREN_NAYAR_PI * a;
  m.sigma = sigma;
  m.white_sky = a * fma(sigma, g_v, (real)OREN_NAYAR_PI);
  /* Eavg = a (pi + sigma G_mean); Eavg / (1 - Eavg) (1 - E(n.v)) = a (pi + sigma G_mean) (G(0) - G(n.v)) / (G(0) - G_mean). */
  const realv sigma_a = sigma * a;
  const realv missing = sigma_a * (OREN_NAYAR_G0 - OREN_NAYAR_G_MEAN);
  const realv ratio = a * fma(sigma, OREN_NAYAR_G_MEAN, (real)OREN_NAYAR_PI) * (OREN_NAYAR_G0 - g_v) /
                      (OREN_NAYAR_G0 - OREN_NAYAR_G_MEAN);
  m.multiple = make_vec3(oren_nayar_multiple(albedo.x, ratio, sigma_a, missing),
                         oren_nayar_multiple(albedo.y, ratio, sigma_a, missing),
                         oren_nayar_multiple(albedo.z, ratio, sigma_a, missing));
  return m;
}

/* The single scattering's response to unit l for unit n and v, over the colour: n.l pi (a + b t), Fujii's
 * t = l.v - n.l n.v, divided by max(n.l, n.v) where positive. 0 where l is below the horizon. */
static inline realv oren_nayar_single(OrenNayarSurface m, realv n_dot_l, realv n_dot_v, realv l_dot_v) {
  const realv nl = max(n_dot_l, (real)0), nv = max(n_dot_v, (real)0);
  const realv s = fma(-nl, nv, l_dot_v);
  const realv t = SELECT(s > 0, s / (max(nl, nv) + (real)FLT_MIN), s);
  return SELECT(n_dot_l > 0, nl * m.single * fma(m.sigma, t, 1), 0);
}

/* What M multiplies for a light from n.l: n.l (G(0) - G(n.l)), 0 below the horizon. */
static inline realv oren_nayar_multiple_weight(realv n_dot_l) {
  const realv nl = clamp(n_dot_l, (real)0, (real)1);
  return nl * (OREN_NAYAR_G0 - oren_nayar_g(nl));
}

/* The response over Lambert's under a white world: E(n.v) + M (G(0) - G_mean) per channel (the mean of
 * G(0) - G(n.l) over the cosine-weighted hemisphere). */
static inline vec3 oren_nayar_white_sky(OrenNayarSurface m) {
  const realv missing = OREN_NAYAR_G0 - OREN_NAYAR_G_MEAN;
  return make_vec3(fma(m.multiple.x, missing, m.white_sky), fma(m.multiple.y, missing, m.white_sky),
                   fma(m.multiple.z, missing, m.white_sky));
}

#endif
