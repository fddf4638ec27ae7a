/* Area lights (layout.h AreaLightRecord): one-sided Lambertian rects and disks. For a vector of pixels
 * at P with unit normal n, where c = centre - P, one adds
 *   diffuse:  Li * E, E = integral over the emitter's part above P's horizon of max(0, n.w) dw
 *   specular: Li * S, S = integral over the same part of max(0, r.w)^q dw, r = 2(n.v)n - v
 * (Li has the diffuse 1/pi folded in, as a point light's: a tiny emitter of area A facing P from
 * distance d is a point light of colour Li * A / d^2). Nothing where P is behind the emitting side.
 * E is Lambert's formula, exact: half the sum over the edges of the angle each subtends times n's dot
 * with the unit normal of the plane through P and the edge, the polygon first clipped to P's
 * horizon; the disk's is in closed form while it is wholly above the horizon. S is a stated
 * approximation: fixed Gauss-Legendre quadrature over the emitter (docs/shading.md "Area lights").
 * Geometry is divided by |c| + the emitter's extent first: every formula here is scale-free, and
 * the products then stay far from float's limits. */
#ifndef PHONGCL_AREA_LIGHT_H
#define PHONGCL_AREA_LIGHT_H

#include "layout.h"
#include "phong_math.h"

/* Below this (emitter diagonal / distance) a rect's E is a 2x2 Gauss rule over its area instead of
 * Lambert's sum, whose terms are O(size / d) and cancel to O((size / d)^2): the rule's error is
 * O((size / d)^4), Lambert's eps * d / size; they meet here (float: about 1e-6 relative). */
#if PHONGCL_DOUBLE
#define AREA_FAR_FIELD 1e-3
#else
#define AREA_FAR_FIELD 0.04f
#endif
#if PHONGCL_DOUBLE
#define AREA_PI M_PI
#else
#define AREA_PI M_PI_F
#endif
/* Vertices of the area-matched polygon that stands in for a disk cut by the horizon. */
#define AREA_DISK_SIDES 64

vec3 add3(vec3 a, vec3 b) { return make_vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
vec3 cross3(vec3 a, vec3 b) {
  return make_vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
vec3 select3(vec3 if_true, vec3 if_false, realv condition) {
  return make_vec3(SELECT(condition != 0, if_true.x, if_false.x), SELECT(condition != 0, if_true.y, if_false.y),
                   SELECT(condition != 0, if_true.z, if_false.z));
}
vec3 area_vector(UNIFORM_SPACE const float* x) { return make_vec3((realv)x[0], (realv)x[1], (realv)x[2]); }

/* The angle edge a -> b subtends at P times n's dot with the unit normal of their plane: the angle
 * as atan2(|a x b|, a.b), which keeps its precision where acos of a dot near 1 would not. */
realv edge_term(vec3 a, vec3 b, vec3 n) {
  const vec3 normal = cross3(a, b);
  const realv sine = sqrt(dot3(normal, normal));
  return SELECT(sine > 0, atan2(sine, dot3(a, b)) * (dot3(n, normal) / sine), 0);
}

/* Lambert's sum over a polygon's edges, clipped to the horizon n.w >= 0 as they come: an edge that
 * leaves the upper side ends at `exit`, one that enters starts at `entry`, and the horizon's own
 * edge from exit to entry is added once at the end (a convex polygon crosses it at most twice). */
typedef struct {
  realv sum;
  vec3 exit, entry;
  realv crosses; /* 1 where an edge crossed the horizon */
} ClippedSum;

void add_clipped_edge(ClippedSum* clipped, vec3 a, vec3 b, vec3 n) {
  const realv ha = dot3(n, a), hb = dot3(n, b);
  const realv a_up = SELECT(ha > 0, 1, 0), b_up = SELECT(hb > 0, 1, 0);
  /* The horizon point of the edge, a convex combination (any positive multiple would do). */
  const realv weight_sum = fabs(ha) + fabs(hb);
  const realv t = SELECT(weight_sum > 0, fabs(ha) / weight_sum, 0);
  const vec3 x = make_vec3(fma(t, b.x - a.x, a.x), fma(t, b.y - a.y, a.y), fma(t, b.z - a.z, a.z));
  const realv term = edge_term(select3(a, x, a_up), select3(b, x, b_up), n);
  clipped->sum += SELECT(a_up + b_up > 0, term, 0);
  const realv leaves = SELECT(a_up > b_up, 1, 0), enters = SELECT(b_up > a_up, 1, 0);
  clipped->exit = select3(x, clipped->exit, leaves);
  clipped->entry = select3(x, clipped->entry, enters);
  clipped->crosses = fmax(clipped->crosses, leaves);
}

/* E from a finished clipped sum. The edges run counter-clockwise about the emitter's normal, which
 * points towards P: seen from P they run clockwise, hence the minus sign. */
realv clipped_irradiance(const ClippedSum* clipped, vec3 n) {
  const realv horizon = SELECT(clipped->crosses != 0, edge_term(clipped->exit, clipped->entry, n), 0);
  return (real)-0.5 * (clipped->sum + horizon);
}

ClippedSum no_clipped_sum(void) {
  const realv zero = 0;
  const ClippedSum empty = {zero, {zero, zero, zero}, {zero, zero, zero}, zero};
  return empty;
}

/* E of a rect: corners c +- u +- v (scaled), counter-clockwise about its normal. */
realv rect_irradiance(vec3 c, vec3 u, vec3 v, vec3 n) {
  const vec3 corner[4] = {add3(c, add3(u, v)), add3(sub3(c, u), v), sub3(sub3(c, u), v), sub3(add3(c, u), v)};
  ClippedSum clipped = no_clipped_sum();
  for (int k = 0; k < 4; ++k) add_clipped_edge(&clipped, corner[k], corner[(k + 1) % 4], n);
  return clipped_irradiance(&clipped, n);
}

/* E of a small rect: the integral of max(0, n.x) h / |x|^4 over its area (h: P's height above it)
 * by the 2x2 Gauss rule, exact to O((size / d)^4). */
realv far_rect_irradiance(vec3 c, vec3 u, vec3 v, vec3 n, realv h, realv area) {
  const real node = (real)0.57735026918962576; /* 1 / sqrt(3) */
  realv sum = 0;
  for (int k = 0; k < 4; ++k) {
    const vec3 x = add3(c, add3(scale3(u, (k & 1) ? node : -node), scale3(v, (k & 2) ? node : -node)));
    const realv length_sq = dot3(x, x);
    sum += fmax(dot3(n, x), 0) / (length_sq * length_sq);
  }
  return sum * h * (area / 4);
}

/* E of a disk of radius a wholly above the horizon, in closed form: its vector irradiance, the
 * form factors from a point at height h and distance r from its axis to a parallel and a
 * perpendicular disk (Siegel and Howell), written without cancellation:
 *   parallel 1/2 (1 - X/Y) = 2 a^2 h^2 / (Y (Y + X)),  perpendicular h/(2r) (Z/Y - 1) = 2 h r a^2 / (Y (Z + Y)),
 *   Z = h^2 + r^2 + a^2, X = Z - 2a^2, Y^2 = Z^2 - 4 r^2 a^2 = (h^2 + (r - a)^2) (h^2 + (r + a)^2). */
realv disk_irradiance(vec3 c, vec3 normal, realv radius_sq, vec3 n, realv h) {
  const vec3 across = make_vec3(fma(h, normal.x, c.x), fma(h, normal.y, c.y), fma(h, normal.z, c.z)); /* towards the axis */
  const realv r = sqrt(dot3(across, across)), a = sqrt(radius_sq), h2 = h * h;
  const realv z = dot3(c, c) + radius_sq, x = z - 2 * radius_sq;
  const realv y = sqrt((h2 + (r - a) * (r - a)) * (h2 + (r + a) * (r + a)));
  const realv parallel = SELECT(x > 0, 2 * radius_sq * h2 / (y * (y + x)), (real)0.5 * (1 - x / y));
  const realv perpendicular_over_r = 2 * h * radius_sq / (y * (z + y));
  return AREA_PI * (perpendicular_over_r * dot3(n, across) - parallel * dot3(n, normal));
}

/* E of a disk cut by the horizon: the clipped sum of the regular AREA_DISK_SIDES-gon of the same
 * area. Not exact: docs/shading.md gives its measured error. */
realv cut_disk_irradiance(vec3 c, vec3 u, vec3 v, vec3 n) {
  const real step = (real)2 / AREA_DISK_SIDES; /* in units of pi */
  /* circumradius R of the n-gon of area pi a^2: n/2 R^2 sin(2 pi / n) = pi a^2 */
  const real stretch = sqrt(2 * AREA_PI / (AREA_DISK_SIDES * sinpi(step)));
  ClippedSum clipped = no_clipped_sum();
  vec3 first = add3(c, scale3(u, stretch)), previous = first;
  for (int k = 1; k <= AREA_DISK_SIDES; ++k) {
    const real angle = k * step;
    const vec3 next = k == AREA_DISK_SIDES ? first
                                           : add3(c, add3(scale3(u, stretch * cospi(angle)), scale3(v, stretch * sinpi(angle))));
    add_clipped_edge(&clipped, previous, next, n);
    previous = next;
  }
  return clipped_irradiance(&clipped, n);
}

/* Gauss-Legendre nodes and weights on [-1, 1], 4 points: the specular rule. */
#define AREA_GAUSS_POINTS 4
static inline real area_gauss_node(int i) {
  return i == 0 ? (real)-0.86113631159405258 : i == 1 ? (real)-0.33998104358485626 : i == 2 ? (real)0.33998104358485626 : (real)0.86113631159405258;
}
static inline real area_gauss_weight(int i) {
  return (i == 0 || i == 3) ? (real)0.34785484513745386 : (real)0.65214515486254614;
}

/* One quadrature point's share of S: weight dA * h / |x|^3 * max(0, r.x/|x|)^q, above the horizon. */
realv specular_sample(vec3 x, vec3 n, vec3 r, realv shininess, realv h, realv weight) {
  const realv inverse = rsqrt(dot3(x, x));
  const vec3 w = scale3(x, inverse);
  const vec3 r_minus_w = sub3(r, w);
  const realv lobe = specular_power(dot3(r, w), (real)0.5 * dot3(r_minus_w, r_minus_w), shininess);
  return SELECT(dot3(n, x) > 0, weight * h * inverse * inverse * inverse * lobe, 0);
}

/* S by a product rule: rect, 4x4 Gauss points over (s, t) in [-1, 1]^2 (dA = |u||v| ds dt); disk,
 * 4 Gauss points in the squared radius times 8 equal angles (equal areas in rho^2, so dA = pi a^2
 * times the Gauss weight / 2 / 8). */
realv area_specular(int shape, vec3 c, vec3 u, vec3 v, vec3 n, vec3 r, realv shininess, realv h, realv area) {
  realv sum = 0;
  if (shape == AREA_RECT) {
    for (int i = 0; i < AREA_GAUSS_POINTS; ++i)
      for (int j = 0; j < AREA_GAUSS_POINTS; ++j) {
        const vec3 x = add3(c, add3(scale3(u, area_gauss_node(i)), scale3(v, area_gauss_node(j))));
        sum += specular_sample(x, n, r, shininess, h, area_gauss_weight(i) * area_gauss_weight(j) * (area / 4));
      }
  } else {
    for (int i = 0; i < AREA_GAUSS_POINTS; ++i) {
      const real rho = sqrt((1 + area_gauss_node(i)) / 2); /* of the radius */
      for (int k = 0; k < 8; ++k) {
        const real angle = (real)(2 * k + 1) / 8; /* in units of pi */
        const vec3 x = add3(c, add3(scale3(u, rho * cospi(angle)), scale3(v, rho * sinpi(angle))));
        sum += specular_sample(x, n, r, shininess, h, area_gauss_weight(i) / 2 * (area / 8));
      }
    }
  }
  return sum;
}

/* Some lane / every lane of a realv comparison. */
#define AREA_ANY_LANE(comparison) (!all_lanes(LANE_MASK(!(comparison))))

/* E and (where `specular`) S of one area light, times its range window, for pixels at p (relative
 * to the eye) with unit normal n and r, the eye vector mirrored about n. */
void area_light_terms(UNIFORM_SPACE const AreaLightRecord* light, vec3 p, vec3 n, vec3 r, realv shininess, int specular,
                      realv* irradiance, realv* highlight) {
  const vec3 c_eye = sub3(area_vector(light->center), p);
  const vec3 normal = area_vector(light->normal);
  const float extent = length((float3)(light->axis_u[0], light->axis_u[1], light->axis_u[2])) +
                       length((float3)(light->axis_v[0], light->axis_v[1], light->axis_v[2]));
  const realv distance = sqrt(dot3(c_eye, c_eye));
  const realv scale = 1 / (distance + extent);
  const vec3 c = scale3(c_eye, scale);
  const vec3 u = scale3(area_vector(light->axis_u), scale), v = scale3(area_vector(light->axis_v), scale);
  const realv area = light->area * scale * scale;
  const realv h = -dot3(c, normal); /* P's height above the emitting side */
  realv window = 1;
  if (light->inverse_range > 0) {
    const realv t = distance * light->inverse_range, t2 = t * t;
    const realv falling = fmax(1 - t2 * t2, 0);
    window = falling * falling;
  }
  realv e;
  if (light->shape == AREA_RECT) {
    e = rect_irradiance(c, u, v, n);
    const realv diagonal_sq = 4 * (dot3(u, u) + dot3(v, v));
    const realv far_limit_sq = (real)(AREA_FAR_FIELD * AREA_FAR_FIELD) * dot3(c, c);
    if (AREA_ANY_LANE(diagonal_sq < far_limit_sq))
      e = SELECT(diagonal_sq < far_limit_sq, far_rect_irradiance(c, u, v, n, h, area), e);
  } else {
    const realv radius_sq = dot3(u, u), n_dot = dot3(n, normal), n_c = dot3(n, c);
    const realv spread = sqrt(fmax(radius_sq * (1 - n_dot * n_dot), 0)); /* the disk's half height over the horizon */
    const realv above = SELECT(n_c > spread, 1, 0), cut = SELECT(n_c > spread || n_c + spread <= 0, 0, 1);
    e = SELECT(above != 0, disk_irradiance(c, normal, radius_sq, n, h), 0);
    if (AREA_ANY_LANE(cut != 0)) e = SELECT(cut != 0, cut_disk_irradiance(c, u, v, n), e);
  }
  *irradiance = SELECT(h > 0, fmax(e, 0) * window, 0);
  *highlight = 0;
  if (specular)
    *highlight = SELECT(h > 0, area_specular(light->shape, c, u, v, n, r, shininess, h, area) * window, 0);
}

#endif
