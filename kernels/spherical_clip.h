/* Clipping a convex spherical polygon, edge by edge as its edges come, to the upper side of planes
 * through the origin (area_light.h's horizon, phong_polygon.h's lobe side). Vertices need not be
 * unit vectors: an edge a -> b stands for the great-circle arc between their directions. */
#ifndef PHONGCL_SPHERICAL_CLIP_H
#define PHONGCL_SPHERICAL_CLIP_H

#include "phong_math.h"

/* Part of edge a -> b on the upper side of the plane with normal `plane`: each end kept where it
 * is above, else replaced by `crossing`, the chord's point on the plane (empty: both ends there). */
typedef struct {
  vec3 a, b, crossing;
  realv a_up, b_up;
} ClippedEdge;

ClippedEdge clip_edge(vec3 a, vec3 b, vec3 plane) {
  const realv ha = dot3(plane, a), hb = dot3(plane, b);
  ClippedEdge e;
  e.a_up = SELECT(ha > 0, 1, 0);
  e.b_up = SELECT(hb > 0, 1, 0);
  /* A convex combination (any positive multiple would do). */
  const realv weight_sum = fabs(ha) + fabs(hb);
  const realv t = SELECT(weight_sum > 0, fabs(ha) / weight_sum, 0);
  e.crossing = make_vec3(fma(t, b.x - a.x, a.x), fma(t, b.y - a.y, a.y), fma(t, b.z - a.z, a.z));
  e.a = select3(a, e.crossing, e.a_up);
  e.b = select3(b, e.crossing, e.b_up);
  return e;
}

/* 1 where some part of the clipped edge is above. */
realv edge_kept(const ClippedEdge* e) { return SELECT(e->a_up + e->b_up > 0, 1, 0); }

/* Where the polygon leaves and re-enters a plane's upper side: the clipped polygon's edge along
 * the plane runs from exit to entry (a convex polygon crosses it at most twice). */
typedef struct {
  vec3 exit, entry;
  realv crosses; /* 1 where an edge left the upper side */
} PlaneCrossings;

PlaneCrossings no_crossings(void) {
  const realv zero = 0;
  const PlaneCrossings none = {{zero, zero, zero}, {zero, zero, zero}, zero};
  return none;
}

void note_crossing(PlaneCrossings* crossings, const ClippedEdge* e) {
  const realv leaves = SELECT(e->a_up > e->b_up, 1, 0), enters = SELECT(e->b_up > e->a_up, 1, 0);
  crossings->exit = select3(e->crossing, crossings->exit, leaves);
  crossings->entry = select3(e->crossing, crossings->entry, enters);
  crossings->crosses = fmax(crossings->crosses, leaves);
}

#endif
