/* Phong's lobe about an axis r over a spherical polygon, in closed form for integer exponents
 * (Arvo 1995, "Applications of irradiance tensors to the simulation of non-Lambertian phenomena";
 * derivation and figures in docs/shading.md "Area lights"). The polygon is clipped to the pixel's
 * horizon n.w >= 0 and, where q > 0, to the lobe's side r.w >= 0; over what is left
 *   I_q = integral of (r.w)^q dw                   (phong)
 *   D_q = integral of (r.w)^q (n.w) dw             (phong-normalized, before its (q+2)/2)
 * from the divergence theorem on the sphere, edge by edge (g the unit normal of the plane through
 * the origin and the edge, theta its angle, J^k the edge's integral of (r.w)^k over its arc length):
 *   (q+1) I_q = [q even] Omega - sum_edges (r.g) sum_{k = q-1, q-3, ... >= 0} J^k
 *   (q+2) D_q = (r.n) q I_{q-1} - sum_edges (n.g) J^q
 *   k J^k = t_a^(k-1) s_a - t_b^(k-1) s_b + (k-1) (1 - (r.g)^2) J^(k-2),  J^0 = theta,  J^1 = s_a - s_b
 * with t = r.w and s = r.(g x w) at the edge's ends a and b, Omega the solid angle. Every step of
 * either recurrence multiplies the error it inherits by less than 1, so rounding does not grow with
 * q; the cost does: q/2 steps per edge. A non-integer q below PHONG_EDGE_RULE_MAX_Q takes the
 * edge rule (edge_rule_flux): the same theorem with a field whose divergence is (r.w)^q for real q,
 *   (q+1) I_q = -sum_edges (r.g) integral of (1 - t^(q+1)) / (1 - t^2)
 *   (q+2) D_q = -sum_edges integral of (n.r) (r.g) (1 - t^(q+2)) / (1 - t^2) + (n.g - (n.r)(r.g)) t^q
 * (no Omega: the fields are smooth on the lobe's side), each edge's integral by a graded Gauss rule.
 * A larger non-integer q takes I (or D) at floor(q) and floor(q) + 1 and interpolates their
 * logarithms: both are log-convex in q (Hoelder), so this is an upper bound, within 1/8 of the
 * variance of log(r.w) under the lobe-weighted measure (about 1/(8 q^2), 5e-4 at q = 16). */
#ifndef PHONGCL_PHONG_POLYGON_H
#define PHONGCL_PHONG_POLYGON_H

#include "features.h"
#include "phong_math.h"
#include "spherical_clip.h"

/* The integer exponents the recurrence runs to; above, area_light.h integrates numerically. */
#define PHONG_POLYGON_MAX_Q 1024
/* Where a length or a logarithm's argument would be 0: a normal float far below any value kept. */
#define PHONG_POLYGON_TINY ((real)0x1p-120)
/* Non-integer exponents below this take the edge rule; from it on, the log-interpolation. */
#define PHONG_EDGE_RULE_MAX_Q 16

/* The polygon's sums so far, per lane: `top` is the highest power of the edge recurrence (q - 1
 * for I, q for D; -1: none), `normalized` 1 where D is wanted. */
typedef struct {
  vec3 n, r;
  vec3 apex;       /* a unit vector near the polygon, from which the solid angle is summed */
  realv lobe_side; /* 1 where the polygon is clipped to r.w >= 0 too */
  realv top, normalized;
  realv rule, exponent; /* rule: 1 in lanes that take the edge rule at the real exponent q */
  realv solid_angle; /* -Omega: Van Oosterom and Strackee's triangles from the apex */
  realv lobe_sum;    /* sum (r.g) (the J^k the formula sums) */
  realv cosine_sum;  /* sum (n.g) J^top, for D */
  realv rule_sum;    /* sum of edge_rule_flux */
  realv highest;     /* the largest r.w on the polygon's boundary */
  realv r_inside;    /* 1 while r.g <= 0 on every edge: r within the (convex) polygon */
  PlaneCrossings horizon, lobe_side_crossings;
} PhongPolygon;

static inline realv is_odd(realv k) { return SELECT(k - 2 * floor(k / 2) != 0, 1, 0); }

/* J^k for k = top, top - 2, ... >= 0 along the arc a -> b (unit vectors, g its unit plane normal):
 * their sum (to *sum) and J^top (to *last). */
void edge_powers(vec3 a, vec3 b, vec3 g, realv theta, vec3 r, realv top, realv* sum, realv* last) {
  const realv t_a = dot3(r, a), t_b = dot3(r, b);
  const realv s_a = dot3(r, cross3(g, a)), s_b = dot3(r, cross3(g, b));
  const realv r_g = dot3(r, g), squeeze = fmax(1 - r_g * r_g, 0);
  const realv odd = is_odd(top);
  realv j = SELECT(odd != 0, s_a - s_b, theta);
  realv power_a = SELECT(odd != 0, t_a * t_a, t_a), power_b = SELECT(odd != 0, t_b * t_b, t_b); /* t^(k-1) */
  realv total = SELECT(top >= 0, j, 0);
  for (realv k = odd + 2; ANY_LANE(k <= top); k += 2) {
    const realv next = ((power_a * s_a - power_b * s_b) + (k - 1) * squeeze * j) / k;
    j = SELECT(k <= top, next, j);
    total += SELECT(k <= top, next, 0);
    power_a *= t_a * t_a;
    power_b *= t_b * t_b;
  }
  *sum = total;
  *last = SELECT(top >= 0, j, 0);
}

/* Gauss-Legendre's 12 points on [0, 1] (nodes 1/2 + x/2, weights halved from [-1, 1]). */
#define EDGE_RULE_POINTS 12
static inline real edge_rule_half_node(int i) { /* x of node i for i < 6; the rest mirror them */
  return i == 0 ? (real)0.98156063424671924 : i == 1 ? (real)0.90411725637047480 : i == 2 ? (real)0.76990267419430469
       : i == 3 ? (real)0.58731795428661748 : i == 4 ? (real)0.36783149899818018 : (real)0.12523340851146894;
}
static inline real edge_rule_half_weight(int i) {
  return i == 0 ? (real)0.04717533638651183 : i == 1 ? (real)0.10693932599531818 : i == 2 ? (real)0.16007832854334633
       : i == 3 ? (real)0.20316742672306584 : i == 4 ? (real)0.23349253653835478 : (real)0.24914704581340288;
}

/* The edge rule's integral along the arc from unit vector a through angle theta in the plane of
 * unit normal g, at real exponent q (the (q+1) I_q or (q+2) D_q formula's term, unsigned): at angle
 * phi, t = r.w = t_a cos + s_a sin and 1 - t^2 = s^2 + (r.g)^2 with s = r.(g x w), without
 * cancellation, and 1 - t^p = -expm1(p log1p(-(1 - t))). The integrand is analytic except t^p
 * where an end lies on r.w = 0 (clipped to the lobe's side); phi = theta (3y^2 - 2y^3) turns that
 * into y^(2p+1), which 12 Gauss points in y integrate to 1e-7 below q = 16 (docs/shading.md). */
realv edge_rule_flux(vec3 a, vec3 g, realv theta, vec3 n, vec3 r, realv q, realv normalized) {
  const realv t_a = dot3(r, a), s_a = dot3(r, cross3(g, a)), r_g = dot3(r, g), r_n = dot3(r, n);
  const realv p = q + 1 + normalized;
  const realv ratio_weight = r_g * SELECT(normalized != 0, r_n, 1);
  const realv power_weight = SELECT(normalized != 0, dot3(n, g) - r_n * r_g, 0);
  realv sum = 0;
  for (int i = 0; i < EDGE_RULE_POINTS; ++i) {
    const real x = i < EDGE_RULE_POINTS / 2 ? edge_rule_half_node(i) : -edge_rule_half_node(EDGE_RULE_POINTS - 1 - i);
    const real weight = edge_rule_half_weight(i < EDGE_RULE_POINTS / 2 ? i : EDGE_RULE_POINTS - 1 - i) / 2;
    const real y = (1 + x) / 2;
    realv cosine;
    const realv sine = sincos(theta * (y * y * (3 - 2 * y)), &cosine);
    const realv t = fmax(t_a * cosine + s_a * sine, 0), s = s_a * cosine - t_a * sine;
    const realv m = s * s + r_g * r_g;                         /* 1 - t^2 */
    const realv e = fmin(m / (1 + t), (real)(1 - 0x1p-24));    /* 1 - t, below 1: log1p stays finite */
    const realv ratio = SELECT(m > PHONG_POLYGON_TINY, -expm1(p * log1p(-e)) / fmax(m, PHONG_POLYGON_TINY), p / 2);
    /* t^q only where a normalised lobe needs it (a scene's models are known when it compiles) */
    const realv power = NORMALIZED_LOBES ? power_weight * exp2(q * log2(fmax(t, PHONG_POLYGON_TINY))) : 0;
    sum += (weight * 6 * y * (1 - y)) * (ratio_weight * ratio + power);
  }
  return theta * sum;
}

/* Adds arc a -> b, already clipped to both planes, in the lanes where `kept` (it may have shrunk
 * to a point: its terms are then 0). */
void add_clipped_arc(PhongPolygon* p, vec3 a_scaled, vec3 b_scaled, realv kept) {
  if (!ANY_LANE(kept != 0)) return;
  /* Lanes that do not keep the arc may hold a zero vector here: every value stays finite (under
   * -cl-fast-relaxed-math an Inf or NaN, even one a select drops, may spread). */
  const vec3 a = scale3(a_scaled, rsqrt(fmax(dot3(a_scaled, a_scaled), PHONG_POLYGON_TINY)));
  const vec3 b = scale3(b_scaled, rsqrt(fmax(dot3(b_scaled, b_scaled), PHONG_POLYGON_TINY)));
  const vec3 normal = cross3(a, b), n = p->n, apex = p->apex;
  const realv sine = sqrt(dot3(normal, normal)), cosine = dot3(a, b);
  const vec3 g = scale3(normal, SELECT(sine > 0, 1 / fmax(sine, PHONG_POLYGON_TINY), 0));
  const realv theta = atan2(sine, cosine);
  realv sum, last;
  edge_powers(a, b, g, theta, p->r, p->top, &sum, &last);
  if (ANY_LANE(p->rule != 0 && kept != 0))
    p->rule_sum += SELECT(p->rule != 0 && kept != 0, edge_rule_flux(a, g, theta, n, p->r, p->exponent, p->normalized), 0);
  const realv triangle = 2 * atan2(dot3(apex, normal), 1 + dot3(apex, a) + dot3(apex, b) + cosine);
  p->solid_angle += SELECT(kept != 0, triangle, 0);
  p->lobe_sum += SELECT(kept != 0, dot3(p->r, g) * SELECT(p->normalized != 0, sum - last, sum), 0);
  p->cosine_sum += SELECT(kept != 0, dot3(n, g) * last, 0);
  /* r.w peaks on the arc where r's projection onto its plane falls between a and b, else at an end */
  const realv r_g = dot3(p->r, g);
  const vec3 closest = sub3(p->r, scale3(g, r_g));
  const realv between = SELECT(dot3(cross3(a, closest), g) >= 0 && dot3(cross3(closest, b), g) >= 0, 1, 0);
  const realv highest = SELECT(between != 0, sqrt(fmax(1 - r_g * r_g, 0)), fmax(dot3(p->r, a), dot3(p->r, b)));
  p->highest = SELECT(kept != 0, fmax(p->highest, highest), p->highest);
  p->r_inside = SELECT(kept != 0 && r_g > 0, 0, p->r_inside);
}

/* Arc a -> b clipped to the lobe's side where the lanes ask for it (where not, as it is). */
void add_arc_on_lobe_side(PhongPolygon* p, vec3 a, vec3 b, realv kept) {
  const ClippedEdge lobe = clip_edge(a, b, p->r);
  add_clipped_arc(p, select3(lobe.a, a, p->lobe_side), select3(lobe.b, b, p->lobe_side),
                  kept * SELECT(p->lobe_side != 0, edge_kept(&lobe), 1));
}

/* An edge of the emitter's polygon (vertices relative to the pixel, counter-clockwise about the
 * emitter's normal, as area_light.h gives them). */
void add_polygon_edge(PhongPolygon* p, vec3 a, vec3 b) {
  const ClippedEdge above = clip_edge(a, b, p->n), lobe = clip_edge(a, b, p->r);
  note_crossing(&p->horizon, &above);
  note_crossing(&p->lobe_side_crossings, &lobe);
  add_arc_on_lobe_side(p, above.a, above.b, edge_kept(&above));
}

/* A polygon for lanes with exponent q (integer, or real where `rule`), normal n and lobe axis r,
 * clipped to the lobe's side where `lobe_side`. `apex`, a unit vector towards the polygon, keeps the solid angle's
 * triangles as small as the polygon (from a far apex they would be large and cancel). Where q = 0 the lobe is 1 everywhere; where r is within 2^-17 of n the
 * horizon's side is the lobe's, up to a lune of width |r - n| < 0.004 in which |r.w|^q < 0.004^q,
 * and clipping to two planes that near each other would be ill-conditioned. */
PhongPolygon start_phong_polygon(vec3 n, vec3 r, vec3 apex, realv q, realv normalized, realv lobe_side, realv rule) {
  const realv zero = 0;
  const realv distinct = SELECT(lobe_side != 0 && dot3(n, r) < 1 - (real)0x1p-17, 1, 0);
  const realv top = SELECT(rule != 0, -1, SELECT(normalized != 0, q, q - 1)); /* the rule's lanes take no steps */
  PhongPolygon p = {n, r, apex, distinct, top, normalized, rule, q,
                    zero, zero, zero, zero, zero, (realv)1, no_crossings(), no_crossings()};
  return p;
}

/* I_q, or D_q without (q+2)/2, of the finished polygon: each plane's own edge, clipped to the
 * other's side, then the formula. */
realv phong_polygon_moment(PhongPolygon* p, realv q) {
  add_arc_on_lobe_side(p, p->horizon.exit, p->horizon.entry, p->horizon.crosses);
  const ClippedEdge lobe = clip_edge(p->lobe_side_crossings.exit, p->lobe_side_crossings.entry, p->n);
  add_clipped_arc(p, lobe.a, lobe.b, p->lobe_side * p->lobe_side_crossings.crosses * edge_kept(&lobe));
  /* Omega enters where the exponent whose I the formula needs (q, or q - 1 for D) is even. */
  const realv needed = SELECT(p->normalized != 0, q - 1, q);
  const realv omega = -p->solid_angle;
  const realv power_sum = SELECT(is_odd(needed) != 0, 0, omega) - p->lobe_sum; /* (q+1) I_q, or q I_{q-1} */
  const realv recurrence = SELECT(p->normalized != 0, (dot3(p->r, p->n) * power_sum - p->cosine_sum) / (q + 2), power_sum / (q + 1));
  const realv moment = SELECT(p->rule != 0, -p->rule_sum / (q + 1 + p->normalized), recurrence);
  /* The formula cancels O(Omega) terms down to the moment, which leaves float an absolute error of
   * a few ulp of Omega. Where r lies outside the polygon the moment is at most Omega times the
   * largest r.w there to the power q, which bounds that error where the lobe barely reaches
   * (raised by 2^-10 so that its own rounding, q ulp at most, never cuts a moment). */
  const realv power = exp2_nonpositive(q * log2(fmax(p->highest, PHONG_POLYGON_TINY)));
  const realv bound = omega * SELECT(p->r_inside != 0 || q == 0, 1, power) * (1 + (real)0x1p-10);
  return clamp(moment, (realv)0, fmax(bound, 0));
}

#endif
