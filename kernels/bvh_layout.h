/* The shadow geometry as the kernels read it (kernels/bvh.h), written once for both languages:
 * fixed-width fields, explicit padding, sizes static-asserted on the host (geometry/device_geometry.h).
 * Every coordinate is relative to the eye, subtracted in double on the host, as the G-buffer's
 * positions are: a scene far from the origin loses nothing in float. */
#ifndef PHONGCL_BVH_LAYOUT_H
#define PHONGCL_BVH_LAYOUT_H

/* The traversal's stack holds one entry per level: the host builds no deeper tree (geometry/bvh.h). */
#define PHONGCL_BVH_MAX_DEPTH 64

/* Shadow rays leave a shaded point by offset_scale * (|P - eye|_inf + |eye|_inf) along its normal
 * (kernels/shadow.h): 8 to 16 float ulp of its world coordinates for positions stored as float,
 * and for half-precision ones (16 half ulp) enough to clear their rounding. */
#define PHONGCL_SHADOW_OFFSET_FLOAT 0x1p-20f
#define PHONGCL_SHADOW_OFFSET_HALF 0x1p-7f

/* What a child link leads to: its kind in the low PHONGCL_BVH_KIND_BITS bits, and for a leaf the
 * number of its primitives above them. An empty child (a root with one leaf) has an empty box. */
enum { BVH_INNER = 0, BVH_TRIANGLES = 1, BVH_SPHERES = 2, BVH_EMPTY = 3 };
#define PHONGCL_BVH_KIND_BITS 2
#define PHONGCL_BVH_KIND_MASK 3u

/* A node of the binary tree holds its two children's boxes (so a visit tests both from one cache
 * line) and links: an inner child's node index, or a leaf's first primitive. Boxes are rounded
 * outwards from double, so they hold every float primitive they bound. */
typedef struct {
  float lo_x[2], lo_y[2], lo_z[2];
  float hi_x[2], hi_y[2], hi_z[2];
  unsigned int first[2];
  unsigned int kind_count[2]; /* kind | count << PHONGCL_BVH_KIND_BITS */
} BvhNode;

/* A triangle: its three corners (rows, w unused), counter-clockwise seen from the front.
 * A sphere in its own space under any affine map (an ellipsoid in the world): the map from an
 * eye-relative point x to the unit sphere's space, u = A x + b, row i of A in row[i][0..2] and b_i
 * in row[i][3]; the surface is |u| = 1. */
typedef struct {
  float row[3][4];
} ShadowPrimitive;

/* An unbounded plane: the points x with dot(normal, x) == offset; normal of unit length. */
typedef struct {
  float normal[3];
  float offset;
} ShadowPlane;

#endif
