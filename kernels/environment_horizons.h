/* The environment's visibility in screen space, horizon-based: GTAO's slices (Jimenez, Wu, Pesce and
 * Jarabo 2016, "Practical realtime strategies for accurate indirect occlusion") with the blocked
 * angles kept as a bitmask of sectors (Therrien, Levesque and Gilet 2023, "Screen space indirect
 * lighting with visibility bitmask") rather than one horizon a side. Around the view direction v the
 * hemisphere is cut into `rays` slices, each the plane through the eye of one image direction
 * (lattice angles, each pixel its own shift). Along a slice the depth plane is sampled on both sides
 * (`steps` a side, out to the image's edge); each sample's surface, `thickness` deep, blocks the
 * angles from its front to its back, two samples of one surface the angles between them too, and a
 * surface that reaches the last sample goes on along its slope as far again (the ground beyond the
 * image's edge). A height field (everything under the highest horizon blocked, GTAO's own rule)
 * made the ground beside an object far behind it dark: 80% of pixels within 5% of Cycles, where
 * these sectors give 96% (docs/environment.md). Each sector's share of the cosine integral is closed
 * form with the normal projected onto the slice; each group of 8 sectors takes the sky's radiance at
 * its blocked sectors' mean angle, times their share, away from E(n) / pi, as environment.h's
 * blocked rays do: exact where nothing rises above the surface's tangent plane. What the camera does
 * not see does not block. */
#ifndef PHONGCL_ENVIRONMENT_HORIZONS_H
#define PHONGCL_ENVIRONMENT_HORIZONS_H

#include "environment.h"
#include "shadow.h"

#define HORIZON_SECTORS 32
#define HORIZON_SECTORS_PER_LOOKUP 8
#if PHONGCL_LANES == 1
#define TO_UINTV(x) convert_uint(x)
#else
#define TO_UINTV(x) PHONGCL_XCAT(convert_uint, PHONGCL_LANES)(x)
#endif

/* The sectors below the index `b` (0 to 32) of a slice's mask. */
static inline uintv sectors_below(uintv b) { return b >= HORIZON_SECTORS ? (uintv)0xffffffffu : (((uintv)1 << b) - 1); }

/* acos to 6.7e-5 (Abramowitz and Stegun 4.4.45), 1/1500 of a sector: the sampling's two a sample
 * were most of the horizons' time with the library's acos. */
static inline realv sector_acos(realv c) {
  const realv a = fabs(c);
  const realv root = sqrt(1 - a) * fma(fma(fma((realv)-0.0187293f, a, (realv)0.0742610f), a, (realv)-0.2121144f), a,
                                       (realv)1.5707288f);
  return SELECT(c < 0, (real)ENVIRONMENT_PI - root, root);
}

/* The angle in a slice of the direction from `origin` toward `to`, from v, positive on the side `sign`. */
static inline realv slice_angle(vec3 origin, vec3 to, vec3 v, realv sign) {
  const vec3 toward = sub3(to, origin);
  return sign * sector_acos(clamp(dot3(toward, v) * rsqrt(dot3(toward, toward)), (realv)-1, (realv)1));
}

/* The sectors of a slice that the depth plane's surfaces block, on the image line from (x, y) along
 * the unit (dx, dy), on the slice's side `sign`: each sample's surface, at its pixel's centre, taken
 * `thickness` deep along the camera's ray (march.thickness as the shadow march reads it), blocks the
 * angles between its front and its back. The sectors split [low, low + pi] evenly. Samples at
 * 1 + (reach - 1) f^2 pixels, f = (j + jitter) / steps: half of them within a quarter of the way
 * to the image's edge, where contact is. */
static inline uintv slice_sectors(__global const float* depth, ScreenMarch march, vec3 origin, vec3 v, vec3 tangent, realv x,
                                  realv y, realv dx, realv dy, realv sign, realv low, realv jitter, intv pending) {
  const vec3 forward = make_vec3(march.forward[0], march.forward[1], march.forward[2]);
  const vec3 right = make_vec3(march.right[0], march.right[1], march.right[2]);
  const vec3 up = make_vec3(march.up[0], march.up[1], march.up[2]);
  const realv huge = (realv)MAXFLOAT, per_sector = (real)(HORIZON_SECTORS / ENVIRONMENT_PI);
  const realv reach_x = SELECT(dx > 0, ((realv)march.width - x) / dx, SELECT(dx < 0, -x / dx, huge));
  const realv reach_y = SELECT(dy > 0, ((realv)march.height - y) / dy, SELECT(dy < 0, -y / dy, huge));
  const realv reach = fmin(reach_x, reach_y);
  pending &= LANE_MASK(reach > 1);
  uintv blocked = 0;
  /* The previous sample's front angle and depth: the surface starts at the shaded point, on the edge
   * of its hemisphere. */
  realv previous_angle = SELECT(sign > 0, low + (real)ENVIRONMENT_PI, low), previous_z = dot3(origin, forward);
  vec3 previous_front = origin, slope_direction = origin;
  realv slope = 0;
  for (uint j = 0; j < march.steps && any_lane(pending); ++j) {
    const realv f = ((realv)j + jitter) / (realv)march.steps;
    const realv r = 1 + (reach - 1) * f * f;
    const realv column = floor(fma(r, dx, x)), row = floor(fma(r, dy, y));
    const realv z = depth_at(depth, march, column, row);
    const realv across = (column + (realv)0.5 - march.centre_x) / march.scale_x;
    const realv down = (row + (realv)0.5 - march.centre_y) / march.scale_y;
    const vec3 front = scale3(add3(forward, sub3(scale3(right, across), scale3(up, down))), z);
    const realv deep = march.thickness < 0 ? -march.thickness : march.thickness / z;
    const realv front_angle = slice_angle(origin, front, v, sign);
    const realv back_angle = slice_angle(origin, scale3(front, 1 + deep), v, sign);
    /* Two samples whose depths differ by less than the thickness are one surface, blocking the angles between them. */
    const realv connected = SELECT(fabs(z - previous_z) < deep * z, 1, 0);
    const realv lowest = fmin(fmin(front_angle, back_angle), SELECT(connected != 0, previous_angle, huge));
    const realv highest = fmax(fmax(front_angle, back_angle), SELECT(connected != 0, previous_angle, -huge));
    /* The surface's last slope, to carry it on past the image's edge. */
    slope = SELECT(connected != 0, 1, 0);
    slope_direction = sub3(front, previous_front);
    previous_front = front;
    previous_angle = front_angle;
    previous_z = z;
    const realv first = clamp(rint((lowest - low) * per_sector), (realv)0, (realv)HORIZON_SECTORS);
    const realv last = clamp(rint((highest - low) * per_sector), (realv)0, (realv)HORIZON_SECTORS);
    const uintv sectors = sectors_below(TO_UINTV(last)) & ~sectors_below(TO_UINTV(first));
    /* The background's infinite depth blocks nothing. */
    blocked |= sectors * TO_UINTV(SELECT(TO_REALV(pending) != 0 && isfinite(z), 1, 0));
  }
  /* A surface that runs out of the samples goes on along its last slope: its far end is seen
   * along that slope's direction (the ground beyond the image's edge). */
  const realv onward = dot3(slope_direction, tangent);
  const vec3 last_reach = sub3(previous_front, origin);
  const realv onward_length = sqrt(dot3(last_reach, last_reach) / dot3(slope_direction, slope_direction));
  const realv far_angle = slice_angle(origin, add3(previous_front, scale3(slope_direction, onward_length)), v, sign);
  const realv ends = SELECT(TO_REALV(pending) != 0 && slope != 0 && onward * sign > 0 && isfinite(previous_z), 1, 0);
  const realv first = clamp(rint((fmin(previous_angle, far_angle) - low) * per_sector), (realv)0, (realv)HORIZON_SECTORS);
  const realv last = clamp(rint((fmax(previous_angle, far_angle) - low) * per_sector), (realv)0, (realv)HORIZON_SECTORS);
  blocked |= (sectors_below(TO_UINTV(last)) & ~sectors_below(TO_UINTV(first))) * TO_UINTV(ends);
  return blocked;
}

/* E(n) / pi of the directions nothing blocks, from the unblocked `light` (E(n) / pi, scaled), for
 * each lane's eye-relative point p and unit normal n; `light` outside `pending`. */
static inline vec3 environment_horizon_light(const ShadowInputs* shadows, UNIFORM_SPACE const EnvironmentRecord* environment,
                                             UNIFORM_SPACE const float* texels, vec3 light, vec3 p, vec3 n,
                                             LatticeShift shift, intv pending) {
  const uint slices = environment->rays;
  if (!any_lane(pending) || slices == 0) return light;
  const ScreenMarch march = shadows->frame.march;
  const vec3 forward = make_vec3(march.forward[0], march.forward[1], march.forward[2]);
  const vec3 right = make_vec3(march.right[0], march.right[1], march.right[2]);
  const vec3 up = make_vec3(march.up[0], march.up[1], march.up[2]);
  const realv z = dot3(p, forward);
  const realv x = march.centre_x + march.scale_x * dot3(p, right) / z;
  const realv y = march.centre_y - march.scale_y * dot3(p, up) / z;
  const vec3 v = scale3(p, -rsqrt(dot3(p, p)));
  /* Lifted off the surface as the shadow march's bias, so that a plane's own pixels stay below its horizon. */
  const vec3 origin = add3(p, scale3(n, z * SCREEN_MARCH_BIAS));
  UNIFORM_SPACE const float* sky = texels + environment->sky_offset;
  const bool uniform_sky = environment->sky_width * environment->sky_height == 1;
  const real sector = (real)(ENVIRONMENT_PI / HORIZON_SECTORS), quarter_turn = (real)(ENVIRONMENT_PI / 2);
  const real turn_cos = cos(2 * sector), turn_sin = sin(2 * sector);
  const realv zero = 0;
  vec3 taken = make_vec3(zero, zero, zero);
  realv blocked = 0, whole = 0;
  for (uint k = 0; k < slices; ++k) {
    realv s, t;
    lattice_point(k, shift, &s, &t);
    const realv angle = (real)ENVIRONMENT_PI * s, dx = cos(angle), dy = sin(angle);
    /* The slice: v and the unit t_dir across it along the image direction (dx, dy), rows growing down. */
    const vec3 along = sub3(scale3(right, dx), scale3(up, dy));
    const vec3 tangent = sub3(along, scale3(v, dot3(along, v)));
    const vec3 t_dir = scale3(tangent, rsqrt(dot3(tangent, tangent)));
    const vec3 axis = cross3(v, t_dir);
    const vec3 projected = sub3(n, scale3(axis, dot3(n, axis)));
    const realv length = sqrt(dot3(projected, projected));
    const realv cos_n = clamp(dot3(projected, v) / fmax(length, (realv)1e-12f), (realv)-1, (realv)1);
    const realv gamma = clamp(SELECT(dot3(projected, t_dir) < 0, -acos(cos_n), acos(cos_n)), -quarter_turn, quarter_turn);
    const realv cos_gamma = cos(gamma), sin_gamma = sin(gamma), low = gamma - quarter_turn;
    const uintv mask = slice_sectors(shadows->depth, march, origin, v, t_dir, x, y, dx, dy, 1, low, t, pending) |
                       slice_sectors(shadows->depth, march, origin, v, t_dir, x, y, -dx, -dy, -1, low, t, pending);
    /* Sector i's share of the cosine integral: A(theta_i+1) - A(theta_i), A(theta) = sign(theta) (cos gamma + 2
     * theta sin gamma + cos(gamma + 2 i sector)) / 4 at theta_i = low + i sector (the antiderivative of
     * cos(theta - gamma) |sin theta|, 0 at theta = 0), the cosine turned sector by sector. */
    realv c = cos_gamma, si = sin_gamma;
    realv previous = SELECT(low < 0, -1, 1) * (realv)0.25 * (cos_gamma + 2 * low * sin_gamma + c);
    realv slice_blocked = 0, group = 0, group_angle = 0;
    for (uint i = 0; i < HORIZON_SECTORS; ++i) {
      const realv next_c = c * turn_cos - si * turn_sin;
      si = si * turn_cos + c * turn_sin;
      c = next_c;
      const realv theta = low + (real)(i + 1) * sector;
      const realv at = SELECT(theta < 0, -1, 1) * (realv)0.25 * (cos_gamma + 2 * theta * sin_gamma + c);
      const realv share = length * (at - previous);
      previous = at;
      const realv taken_share = SELECT(TO_REALV((mask >> i) & 1) != 0, share, 0);
      group += taken_share;
      group_angle += taken_share * (theta - (real)0.5 * sector);
      if ((i + 1) % HORIZON_SECTORS_PER_LOOKUP != 0) continue;
      /* The sky's radiance at the blocked sectors' mean angle in each group of sectors, over their share. */
      if (!uniform_sky && ANY_LANE(group > 0)) {
        const realv middle = group_angle / fmax(group, (realv)FLT_MIN);
        const vec3 d = add3(scale3(v, cos(middle)), scale3(t_dir, sin(middle)));
        taken = add3(taken, scale3(environment_grid(environment, sky, environment->sky_width, environment->sky_height, d), group));
      }
      slice_blocked += group;
      group = 0;
      group_angle = 0;
    }
    whole += length * (cos_gamma + gamma * sin_gamma);
    blocked += slice_blocked;
  }
  if (uniform_sky) { /* every blocked sector takes the one texel's radiance away */
    const realv scale = blocked * environment->scale;
    taken = make_vec3(scale * sky[0], scale * sky[1], scale * sky[2]);
  }
  const realv per_whole = 1 / whole;
  const vec3 visible = make_vec3(fmax(light.x - taken.x * per_whole, zero), fmax(light.y - taken.y * per_whole, zero),
                                 fmax(light.z - taken.z * per_whole, zero));
  return select3(visible, light, SELECT(TO_REALV(pending) != 0, 1, 0));
}

#endif
