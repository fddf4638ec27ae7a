/* The environment light: the world's radiance from every direction (docs/environment.md).
 * Diffuse: the host convolves the map with the cosine lobe once per map (host/environment/), and the
 * kernel reads E(n) / pi bilinearly from that small irradiance map, in Blender's equirectangular
 * mapping (Cycles' direction_to_equirectangular: u = 1/2 - atan2(y, x) / 2pi, the image's top row
 * at +Z). With ENVIRONMENT_SHADOWS each of `rays` cosine-distributed directions that something
 * blocks takes the sky's radiance in its direction away from that light (exact where every ray is
 * free or every ray blocked), traced against the BVH as a directional light's shadow ray is (with
 * SCREEN_SHADOWS the horizons of environment_horizons.h take their place). The map's
 * brightest cells (a sun) are taken out of the irradiance map by the host and come as directional
 * lights: E bends at their horizon faster than the bilinear lookup follows, and each casts a sharp
 * shadow from one ray, as the sun does in Cycles. */
#ifndef PHONGCL_ENVIRONMENT_H
#define PHONGCL_ENVIRONMENT_H

#include "layout.h"
#include "sampling.h"
#include "shadow.h"
#include "soft_shadow.h"

#define ENVIRONMENT_PI 3.14159265358979323846

/* One direction's value in an equirect grid of width x height RGB texels, bilinear between texel
 * centres: wrapping around in longitude, clamped at the top and bottom rows' centres. */
static inline void equirect_lookup(UNIFORM_SPACE const float* texels, int width, int height, real x, real y, real z,
                                   real* rgb) {
  const real u = (real)0.5 - atan2(y, x) * (real)(0.5 / ENVIRONMENT_PI);
  const real t = acos(clamp(z, (real)-1, (real)1)) * (real)(1 / ENVIRONMENT_PI);
  const real fx = u * width - (real)0.5, fy = clamp(t * height - (real)0.5, (real)0, (real)(height - 1));
  const real x_floor = floor(fx), y_floor = floor(fy);
  const real wx = fx - x_floor, wy = fy - y_floor;
  const int x0 = ((int)x_floor % width + width) % width, x1 = (x0 + 1) % width;
  const int y0 = (int)y_floor, y1 = min(y0 + 1, height - 1);
  UNIFORM_SPACE const float* row0 = texels + 3 * (size_t)y0 * width;
  UNIFORM_SPACE const float* row1 = texels + 3 * (size_t)y1 * width;
  for (int c = 0; c < 3; ++c) {
    const real top = row0[3 * x0 + c] + wx * (row0[3 * x1 + c] - row0[3 * x0 + c]);
    const real bottom = row1[3 * x0 + c] + wx * (row1[3 * x1 + c] - row1[3 * x0 + c]);
    rgb[c] = top + wy * (bottom - top);
  }
}

/* Each lane's eye-frame direction d looked up in a grid of the map (the map's frame, then the grid
 * lane by lane: atan2 and acos once per lane; OpenCL C has no vector gather), times the scale. */
static inline vec3 environment_grid(UNIFORM_SPACE const EnvironmentRecord* environment, UNIFORM_SPACE const float* texels,
                                    int width, int height, vec3 d) {
  UNIFORM_SPACE const float* m = environment->to_map;
  const vec3 row_x = make_vec3((realv)m[0], (realv)m[1], (realv)m[2]);
  const vec3 row_y = make_vec3((realv)m[4], (realv)m[5], (realv)m[6]);
  const vec3 row_z = make_vec3((realv)m[8], (realv)m[9], (realv)m[10]);
  const realv x = dot3(row_x, d), y = dot3(row_y, d), z = dot3(row_z, d);
  const real scale = environment->scale;
#if PHONGCL_LANES == 1
  real rgb[3];
  equirect_lookup(texels, width, height, x, y, z, rgb);
  return make_vec3(rgb[0] * scale, rgb[1] * scale, rgb[2] * scale);
#else
  real xs[PHONGCL_LANES], ys[PHONGCL_LANES], zs[PHONGCL_LANES], r[PHONGCL_LANES], g[PHONGCL_LANES], b[PHONGCL_LANES];
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(x, 0, xs);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(y, 0, ys);
  PHONGCL_XCAT(vstore, PHONGCL_LANES)(z, 0, zs);
  for (int k = 0; k < PHONGCL_LANES; ++k) {
    real rgb[3];
    equirect_lookup(texels, width, height, xs[k], ys[k], zs[k], rgb);
    r[k] = rgb[0] * scale;
    g[k] = rgb[1] * scale;
    b[k] = rgb[2] * scale;
  }
  return make_vec3(PHONGCL_XCAT(vload, PHONGCL_LANES)(0, r), PHONGCL_XCAT(vload, PHONGCL_LANES)(0, g),
                   PHONGCL_XCAT(vload, PHONGCL_LANES)(0, b));
#endif
}

/* E(n) / pi for each lane's unit normal, scaled. */
static inline vec3 environment_irradiance(UNIFORM_SPACE const EnvironmentRecord* environment,
                                          UNIFORM_SPACE const float* texels, vec3 n) {
  return environment_grid(environment, texels, environment->width, environment->height, n);
}

/* E(n) / pi of the directions nothing blocks, from the unblocked `light` (E(n) / pi, scaled) and
 * `rays` cosine-distributed directions about n (Malley's method over the shifted R2 lattice: a point
 * of the unit disk lifted to the hemisphere): each blocked ray takes away the sky's radiance in its
 * direction over `rays` (the estimate of the blocked part of the cosine integral, over pi). Exact
 * where no ray is blocked, and 0 where every ray is; unbiased between, where the ratio of free rays
 * times E would take the average sky away for a ray blocked towards the dark ground. In the lanes of
 * `pending`; `light` elsewhere. The rays are directional lights' (to infinity, every one traversing
 * the BVH: tiled shadow culling's lists are per light direction). */
static inline SHADOW_INLINE vec3 environment_visible_light(const ShadowInputs* shadows,
                                                           UNIFORM_SPACE const EnvironmentRecord* environment,
                                                           UNIFORM_SPACE const float* texels, vec3 light, vec3 p,
                                                           vec3 n, LatticeShift shift, intv pending) {
  const uint rays = environment->rays;
  if (!any_lane(pending) || rays == 0) return light;
  ShadowInputs traced = *shadows;
  traced.tiles = 0;
  UNIFORM_SPACE const float* sky = texels + environment->sky_offset;
  /* A uniform world's sky (one texel) needs no look-up per blocked ray: those
   * (atan2 and acos lane by lane) made 16 rays 3 times slower than the rays alone. */
  const bool uniform_sky = environment->sky_width * environment->sky_height == 1;
  const realv zero = 0;
  vec3 taken = make_vec3(zero, zero, zero);
  realv free = 0;
  vec3 u, v;
  orthonormal_basis(n, &u, &v);
  for (uint k = 0; k < rays; ++k) {
    realv s, t;
    lattice_point(k, shift, &s, &t);
    const realv radius = sqrt(s), angle = (real)(2 * ENVIRONMENT_PI) * t;
    const realv height = sqrt(fmax(1 - s, (realv)0));
    const vec3 d = add3(add3(scale3(u, radius * cos(angle)), scale3(v, radius * sin(angle))), scale3(n, height));
    const intv blocked = light_blocked(&traced, p, n, d, 1, 0, 0, pending);
    free += SELECT(TO_REALV(blocked) != 0, 0, 1);
    if (!uniform_sky && any_lane(blocked)) {
      const vec3 radiance = environment_grid(environment, sky, environment->sky_width, environment->sky_height, d);
      const realv weight = SELECT(TO_REALV(blocked) != 0, 1, 0);
      taken = add3(taken, scale3(radiance, weight));
    }
  }
  if (uniform_sky) { /* every blocked ray takes the one texel's radiance away */
    const realv blocked_rays = (real)rays - free, scale = environment->scale;
    taken = make_vec3(blocked_rays * (scale * sky[0]), blocked_rays * (scale * sky[1]), blocked_rays * (scale * sky[2]));
  }
  const real per_ray = (real)1 / (real)rays;
  const realv open = SELECT(free > 0, 1, 0); /* every ray blocked: none of the light */
  const realv traced_lane = SELECT(TO_REALV(pending) != 0, 1, 0);
  const vec3 visible = make_vec3(open * fmax(light.x - taken.x * per_ray, zero), open * fmax(light.y - taken.y * per_ray, zero),
                                 open * fmax(light.z - taken.z * per_ray, zero));
  return add3(scale3(visible, traced_lane), scale3(light, 1 - traced_lane));
}

static inline vec3 environment_sun_direction(UNIFORM_SPACE const EnvironmentSun* sun) {
  return make_vec3((realv)sun->direction[0], (realv)sun->direction[1], (realv)sun->direction[2]);
}

/* 1 in the lanes that see a sun in unit direction d, 0 where n.d <= 0 or, with ENVIRONMENT_SHADOWS,
 * where its ray is blocked (traced in the lanes of `pending`; `traced` without tiled lists). */
static inline SHADOW_INLINE realv environment_sun_visible(const ShadowInputs* traced, vec3 d, vec3 p, vec3 n, intv pending) {
  const realv facing = dot3(n, d);
  if (!ENVIRONMENT_SHADOWS) return SELECT(facing > 0, 1, 0);
  const intv blocked = light_blocked(traced, p, n, d, 1, SCREEN_SHADOWS, 0, pending & LANE_MASK(facing > 0));
  return SELECT(facing > 0 && TO_REALV(blocked) == 0, 1, 0);
}

/* The suns' E / pi, each color max(0, n.d), with ENVIRONMENT_SHADOWS 0 in the lanes where its ray is
 * blocked; `pending`: the lanes that trace. */
static inline SHADOW_INLINE vec3 environment_suns(UNIFORM_SPACE const EnvironmentSun* suns, int count,
                                                  const ShadowInputs* shadows, vec3 p, vec3 n, intv pending) {
  const realv zero = 0;
  vec3 sum = make_vec3(zero, zero, zero);
  ShadowInputs traced = *shadows;
  traced.tiles = 0;
  for (int k = 0; k < count; ++k) {
    UNIFORM_SPACE const EnvironmentSun* sun = &suns[k];
    const vec3 d = environment_sun_direction(sun);
    const realv lit = fmax(dot3(n, d), (realv)0) * environment_sun_visible(&traced, d, p, n, pending);
    sum = add3(sum, make_vec3(lit * sun->color[0], lit * sun->color[1], lit * sun->color[2]));
  }
  return sum;
}

#endif
