/* Area lights (layout.h AreaLightRecord): one-sided Lambertian rects and disks. For a vector of pixels
 * at P with unit normal n, where c = centre - P, one adds
 *   diffuse:  Li * E, E = integral over the emitter's part above P's horizon of max(0, n.w) dw
 *   specular: Li * S, S = integral over the same part of the material's lobe towards w (specular.h;
 *             a normalised lobe's n.w included, its (q+c)/c applied once per pixel by phong.cl)
 * (Li has the diffuse 1/pi folded in, as a point light's: a tiny emitter of area A facing P from
 * distance d is a point light of colour Li * A / d^2). Nothing where P is behind the emitting side.
 * E is Lambert's formula, exact: half the sum over the edges of the angle each subtends times n's dot
 * with the unit normal of the plane through P and the edge, the polygon first clipped to P's
 * horizon; the disk's is in closed form while it is wholly above the horizon. S of Phong's lobes is
 * Arvo's closed form over the same polygon (phong_polygon.h); Blinn's is a stated approximation,
 * fixed Gauss-Legendre quadrature over the emitter (docs/shading.md "Area lights").
 * Geometry is divided by |c| + the emitter's extent first: every formula here is scale-free, and
 * the products then stay far from float's limits. */
#ifndef PHONGCL_AREA_LIGHT_H
#define PHONGCL_AREA_LIGHT_H

#include "layout.h"
#include "phong_math.h"
#include "phong_polygon.h"
#include "specular.h"
#include "spherical_clip.h"

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
/* Sides of the inscribed polygon whose Phong moments, plus its rim's, make a disk's S: each edge
 * costs q/2 recurrence steps (phong_polygon.h). */
#define PHONG_DISK_SIDES 64

vec3 area_vector(UNIFORM_SPACE const float* x) { return make_vec3((realv)x[0], (realv)x[1], (realv)x[2]); }

/* The angle edge a -> b subtends at P times n's dot with the unit normal of their plane: the angle
 * as atan2(|a x b|, a.b), which keeps its precision where acos of a dot near 1 would not. */
realv edge_term(vec3 a, vec3 b, vec3 n) {
  const vec3 normal = cross3(a, b);
  const realv sine = sqrt(dot3(normal, normal));
  return SELECT(sine > 0, atan2(sine, dot3(a, b)) * (dot3(n, normal) / sine), 0);
}

/* Lambert's sum over a polygon's edges, clipped to the horizon n.w >= 0 as they come, and the
 * horizon's own edge added once at the end. */
typedef struct {
  realv sum;
  PlaneCrossings horizon;
} ClippedSum;

void add_clipped_edge(ClippedSum* clipped, vec3 a, vec3 b, vec3 n) {
  const ClippedEdge above = clip_edge(a, b, n);
  const realv term = edge_term(above.a, above.b, n);
  clipped->sum += SELECT(edge_kept(&above) != 0, term, 0);
  note_crossing(&clipped->horizon, &above);
}

/* E from a finished clipped sum. The edges run counter-clockwise about the emitter's normal, which
 * points towards P: seen from P they run clockwise, hence the minus sign. */
realv clipped_irradiance(const ClippedSum* clipped, vec3 n) {
  const realv horizon = SELECT(clipped->horizon.crosses != 0, edge_term(clipped->horizon.exit, clipped->horizon.entry, n), 0);
  return (real)-0.5 * (clipped->sum + horizon);
}

ClippedSum no_clipped_sum(void) {
  const realv zero = 0;
  const ClippedSum empty = {zero, no_crossings()};
  return empty;
}

/* Vertex k of the emitter's polygon, counter-clockwise about its normal: a rect's corners
 * c +- u +- v (scaled); for a disk, the regular `sides`-gon of circumradius `stretch` times the
 * disk's. */
vec3 emitter_vertex(int shape, vec3 c, vec3 u, vec3 v, int k, int sides, real stretch) {
  if (shape == AREA_RECT) {
    const real su = (k == 0 || k == 3) ? 1 : -1, sv = k < 2 ? 1 : -1;
    return add3(c, add3(scale3(u, su), scale3(v, sv)));
  }
  const real angle = k * ((real)2 / sides); /* in units of pi */
  return add3(c, add3(scale3(u, stretch * cospi(angle)), scale3(v, stretch * sinpi(angle))));
}

/* The stretch of the AREA_DISK_SIDES-gon of the disk's area, which E takes for a disk cut by the
 * horizon: circumradius R of the n-gon of area pi a^2, n/2 R^2 sin(2 pi / n) = pi a^2. */
#define AREA_MATCHED_STRETCH sqrt(2 * AREA_PI / (AREA_DISK_SIDES * sinpi((real)2 / AREA_DISK_SIDES)))

/* E of the emitter's polygon by the clipped Lambert sum. */
realv polygon_irradiance(int shape, vec3 c, vec3 u, vec3 v, vec3 n) {
  const int sides = shape == AREA_RECT ? 4 : AREA_DISK_SIDES;
  ClippedSum clipped = no_clipped_sum();
  vec3 previous = emitter_vertex(shape, c, u, v, 0, sides, AREA_MATCHED_STRETCH);
  for (int k = 1; k <= sides; ++k) {
    const vec3 next = emitter_vertex(shape, c, u, v, k % sides, sides, AREA_MATCHED_STRETCH);
    add_clipped_edge(&clipped, previous, next, n);
    previous = next;
  }
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

/* Gauss-Legendre nodes and weights on [-1, 1], 4 points: the numerical rule. */
#define AREA_GAUSS_POINTS 4
static inline real area_gauss_node(int i) {
  return i == 0 ? (real)-0.86113631159405258 : i == 1 ? (real)-0.33998104358485626 : i == 2 ? (real)0.33998104358485626 : (real)0.86113631159405258;
}
static inline real area_gauss_weight(int i) {
  return (i == 0 || i == 3) ? (real)0.34785484513745386 : (real)0.65214515486254614;
}

/* The lanes' specular model, as specular.h numbers them, and what it asks of an area light. */
typedef struct {
  vec3 view;         /* unit vector to the eye */
  realv model;       /* read only where lanes may differ */
  realv normalized;  /* 1: the lobe takes n.w (its (q+c)/c comes once per pixel, in phong.cl) */
  realv half_vector; /* 1: Blinn's lobe */
} AreaLobe;

/* One quadrature point's share of S: weight dA * h / |x|^3 times the lane's lobe towards x (and
 * n.w where normalised), above the horizon. */
realv specular_sample(vec3 x, vec3 n, const AreaLobe* lobe, realv shininess, realv h, realv weight) {
  const realv inverse = rsqrt(dot3(x, x)), n_dot = dot3(n, x);
  const LobeCosine cosine = lobe_cosine(n, lobe->view, x, inverse, n_dot, lobe->model);
  const realv power = specular_power(cosine.cosine, cosine.one_minus_cosine, shininess);
  const realv value = power * SELECT(lobe->normalized != 0, n_dot * inverse, 1);
  return SELECT(n_dot > 0, weight * h * inverse * inverse * inverse * value, 0);
}

/* S by a product rule: rect, 4x4 Gauss points over (s, t) in [-1, 1]^2 (dA = |u||v| ds dt); disk,
 * 4 Gauss points in the squared radius times 8 equal angles (equal areas in rho^2, so dA = pi a^2
 * times the Gauss weight / 2 / 8). An approximation, for the lobes phong_polygon.h cannot take. */
realv numerical_specular(int shape, vec3 c, vec3 u, vec3 v, vec3 n, const AreaLobe* lobe, realv shininess, realv h,
                         realv area) {
  realv sum = 0;
  if (shape == AREA_RECT) {
    for (int i = 0; i < AREA_GAUSS_POINTS; ++i)
      for (int j = 0; j < AREA_GAUSS_POINTS; ++j) {
        const vec3 x = add3(c, add3(scale3(u, area_gauss_node(i)), scale3(v, area_gauss_node(j))));
        sum += specular_sample(x, n, lobe, shininess, h, area_gauss_weight(i) * area_gauss_weight(j) * (area / 4));
      }
  } else {
    for (int i = 0; i < AREA_GAUSS_POINTS; ++i) {
      const real rho = sqrt((1 + area_gauss_node(i)) / 2); /* of the radius */
      for (int k = 0; k < 8; ++k) {
        const real angle = (real)(2 * k + 1) / 8; /* in units of pi */
        const vec3 x = add3(c, add3(scale3(u, rho * cospi(angle)), scale3(v, rho * sinpi(angle))));
        sum += specular_sample(x, n, lobe, shininess, h, area_gauss_weight(i) / 2 * (area / 8));
      }
    }
  }
  return sum;
}

/* Phong's I_q or D_q (phong_polygon.h) over the emitter's polygon (a disk's inscribed
 * PHONG_DISK_SIDES-gon) at an integer exponent per lane. */
realv polygon_moment(int shape, vec3 c, vec3 u, vec3 v, vec3 n, vec3 r, realv exponent, realv normalized, realv lobe_side,
                     realv rule) {
  PhongPolygon polygon = start_phong_polygon(n, r, scale3(c, rsqrt(dot3(c, c))), exponent, normalized, lobe_side, rule);
  const int sides = shape == AREA_RECT ? 4 : PHONG_DISK_SIDES;
  vec3 previous = emitter_vertex(shape, c, u, v, 0, sides, 1);
  for (int k = 1; k <= sides; ++k) {
    const vec3 next = emitter_vertex(shape, c, u, v, k % sides, sides, 1);
    add_polygon_edge(&polygon, previous, next);
    previous = next;
  }
  return phong_polygon_moment(&polygon, exponent);
}

/* S over the part of a disk outside its inscribed PHONG_DISK_SIDES-gon: thin circular segments
 * (height 1 - cos(pi / sides) = 1.2e-3 of the radius), each by 4 Gauss points along its chord, each
 * weighted by the segment's height there above the horizon and taken at that part's middle: the
 * horizon, where the classic lobes jump to 0, is followed across the height exactly. */
realv disk_rim_specular(vec3 c, vec3 u, vec3 v, vec3 n, vec3 r, const AreaLobe* lobe, realv shininess, realv h,
                        realv area) {
  const real half_chord = sinpi((real)1 / PHONG_DISK_SIDES), inner = cospi((real)1 / PHONG_DISK_SIDES);
  const realv n_c = dot3(n, c), n_u = dot3(n, u), n_v = dot3(n, v);
  const realv r_c = dot3(r, c), r_u = dot3(r, u), r_v = dot3(r, v);
  realv sum = 0;
  for (int k = 0; k < PHONG_DISK_SIDES; ++k) {
    const real middle = (real)(2 * k + 1) / PHONG_DISK_SIDES; /* the chord's middle, in units of pi */
    const real cosine = cospi(middle), sine = sinpi(middle);
    const realv n_out = n_u * cosine + n_v * sine; /* n's dot with the outward radial direction */
    /* The segment lies in the triangle of its chord's ends and their tangents' meeting point: where
     * that is below the horizon, or (q > 0) below r.w = 0, in every lane, it adds nothing. */
    const realv n_across = half_chord * (n_v * cosine - n_u * sine), r_across = half_chord * (r_v * cosine - r_u * sine);
    const realv r_out = r_u * cosine + r_v * sine;
    const realv n_high = n_c + fmax(inner * n_out + fabs(n_across), n_out / inner);
    const realv r_high = r_c + fmax(inner * r_out + fabs(r_across), r_out / inner);
    if (!ANY_LANE(n_high > 0 && (r_high > 0 || shininess == 0))) continue;
    for (int i = 0; i < AREA_GAUSS_POINTS; ++i) {
      const real along = half_chord * area_gauss_node(i), rim = sqrt(1 - along * along);
      /* n.x = n_base + radial * n_out along the height; the part where it is > 0 */
      const realv n_base = n_c + along * (n_v * cosine - n_u * sine);
      const realv root = -n_base / SELECT(n_out == 0, 1, n_out);
      const realv low = SELECT(n_out > 0, fmax(inner, root), inner), high = SELECT(n_out < 0, fmin(rim, root), rim);
      const realv height = SELECT(n_out == 0, SELECT(n_base > 0, rim - inner, 0), fmax(high - low, 0));
      const realv radial = SELECT(n_out == 0, (real)0.5 * (inner + rim), (real)0.5 * (low + high));
      const vec3 x = add3(c, add3(scale3(u, radial * cosine - along * sine), scale3(v, radial * sine + along * cosine)));
      /* dA = a^2 d(along) d(radial), a^2 = area / pi */
      sum += specular_sample(x, n, lobe, shininess, h, area_gauss_weight(i) * half_chord * height * (area / AREA_PI));
    }
  }
  return sum;
}

/* Phong's S at any q up to PHONG_POLYGON_MAX_Q over the emitter's polygon: exact at integers; a
 * non-integer q below PHONG_EDGE_RULE_MAX_Q by the edge rule, above it the geometric mean of the
 * integer neighbours weighted by the fraction, an upper bound (phong_polygon.h). */
realv phong_polygon_specular(int shape, vec3 c, vec3 u, vec3 v, vec3 n, vec3 r, realv shininess, realv normalized) {
  /* Lanes beyond the closed form's range take none of its steps (area_specular replaces them). */
  const realv q = SELECT(shininess > PHONG_POLYGON_MAX_Q, 0, shininess), low = floor(q), fraction = q - low;
  const realv lobe_side = SELECT(q > 0, 1, 0);
  const realv rule = SELECT(fraction > 0 && q < PHONG_EDGE_RULE_MAX_Q, 1, 0);
  const realv at_low = polygon_moment(shape, c, u, v, n, r, SELECT(rule != 0, q, low), normalized, lobe_side, rule);
  const realv interpolated = SELECT(fraction > 0 && rule == 0, 1, 0);
  if (!ANY_LANE(interpolated != 0)) return at_low;
  const realv at_high = polygon_moment(shape, c, u, v, n, r, low + 1, normalized, lobe_side, 0);
  const realv between = at_low * exp2(fraction * log2(fmax(at_high / fmax(at_low, PHONG_POLYGON_TINY), PHONG_POLYGON_TINY)));
  return SELECT(interpolated != 0 && at_low > 0, between, at_low);
}

/* S in each lane's model: Phong's lobes in closed form (a disk's as its inscribed polygon's plus
 * the rim's), Blinn's (and Phong's beyond PHONG_POLYGON_MAX_Q) by the numerical rule. */
realv area_specular(int shape, vec3 c, vec3 u, vec3 v, vec3 n, vec3 r, const AreaLobe* lobe, realv shininess, realv h,
                    realv area) {
  /* A far emitter, as E's far field: the closed form's edge terms are O(size / d) and cancel to
   * S = O((size / d)^2), while the rule's error is O((size / d)^4) where the lobe is broader than
   * the emitter (q (size / d)^2 < 1). */
  const realv far = SELECT(4 * (dot3(u, u) + dot3(v, v)) < (real)(AREA_FAR_FIELD * AREA_FAR_FIELD) * dot3(c, c), 1, 0);
  const realv numerical = SELECT(lobe->half_vector != 0 || shininess > PHONG_POLYGON_MAX_Q || far != 0, 1, 0);
  realv s = 0;
  /* Phong's lobe (q > 0) is 0 over an emitter wholly behind the plane r.w = 0: its highest point
   * there is r.c + |r.u| + |r.v| (rect) or r.c + a |r projected on the disk's plane| (disk). */
  const realv r_c = dot3(r, c), r_u = dot3(r, u), r_v = dot3(r, v);
  const realv r_high = r_c + (shape == AREA_RECT ? fabs(r_u) + fabs(r_v) : sqrt(r_u * r_u + r_v * r_v));
  const realv lit = SELECT(shininess == 0 || r_high > 0, 1, 0);
  if (ANY_LANE(numerical == 0 && lit != 0)) {
    s = phong_polygon_specular(shape, c, u, v, n, r, shininess, lobe->normalized);
    if (shape == AREA_DISK) s += disk_rim_specular(c, u, v, n, r, lobe, shininess, h, area);
  }
  if (ANY_LANE(numerical != 0)) s = SELECT(numerical != 0, numerical_specular(shape, c, u, v, n, lobe, shininess, h, area), s);
  return s;
}

/* The light's range window at `distance` from its centre, as a point light's: 1 without a range. */
realv area_range_window(UNIFORM_SPACE const AreaLightRecord* light, realv distance) {
  if (!(light->inverse_range > 0)) return 1;
  const realv t = distance * light->inverse_range, t2 = t * t;
  const realv falling = fmax(1 - t2 * t2, 0);
  return falling * falling;
}

/* E and (where `specular`) S of one area light, times its range window, for pixels at p (relative
 * to the eye) with unit normal n, unit vector to the eye `view`, r the eye vector mirrored about n,
 * and specular model `model` (specular.h's number; read only where lanes may differ). */
void area_light_terms(UNIFORM_SPACE const AreaLightRecord* light, vec3 p, vec3 n, vec3 view, vec3 r, realv shininess,
                      realv model, int specular, realv* irradiance, realv* highlight) {
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
  const realv window = area_range_window(light, distance);
  realv e;
  if (light->shape == AREA_RECT) {
    e = polygon_irradiance(AREA_RECT, c, u, v, n);
    const realv diagonal_sq = 4 * (dot3(u, u) + dot3(v, v));
    const realv far_limit_sq = (real)(AREA_FAR_FIELD * AREA_FAR_FIELD) * dot3(c, c);
    if (ANY_LANE(diagonal_sq < far_limit_sq))
      e = SELECT(diagonal_sq < far_limit_sq, far_rect_irradiance(c, u, v, n, h, area), e);
  } else {
    const realv radius_sq = dot3(u, u), n_dot = dot3(n, normal), n_c = dot3(n, c);
    const realv spread = sqrt(fmax(radius_sq * (1 - n_dot * n_dot), 0)); /* the disk's half height over the horizon */
    const realv above = SELECT(n_c > spread, 1, 0), cut = SELECT(n_c > spread || n_c + spread <= 0, 0, 1);
    e = SELECT(above != 0, disk_irradiance(c, normal, radius_sq, n, h), 0);
    if (ANY_LANE(cut != 0)) e = SELECT(cut != 0, polygon_irradiance(AREA_DISK, c, u, v, n), e);
  }
  *irradiance = SELECT(h > 0, fmax(e, 0) * window, 0);
  *highlight = 0;
  if (specular) {
    const AreaLobe lobe = {view, model, normalized_model(model),
                           !HALF_VECTOR_LOBES ? 0 : !REFLECTION_LOBES ? 1 : SELECT(model >= 2, 1, 0)};
    *highlight = SELECT(h > 0, area_specular(light->shape, c, u, v, n, r, &lobe, shininess, h, area) * window, 0);
  }
}

#endif
