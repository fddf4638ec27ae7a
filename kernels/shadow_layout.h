/* What shadows read on the device, written once for both languages: the scene's geometry and its BVH
 * (kernels/bvh.h), tiled shadow culling's lists (shadow_cull.cl) and the screen-space march's camera
 * (shadow.h). Fixed-width fields, explicit padding, sizes static-asserted on the host
 * (geometry/device_geometry.h). Every coordinate is relative to the eye, subtracted in double on the
 * host, as the G-buffer's positions are: a scene far from the origin loses nothing in float. */
#ifndef PHONGCL_SHADOW_LAYOUT_H
#define PHONGCL_SHADOW_LAYOUT_H

/* The traversal's stack holds one entry per level: the host builds no deeper tree (geometry/bvh.h). */
#define PHONGCL_BVH_MAX_DEPTH 64

/* Shadow rays leave a shaded point by offset_scale * (|P - eye|_inf + |eye|_inf) along its normal
 * (kernels/shadow.h): 8 to 16 float ulp of its world coordinates for positions stored as float,
 * and for half-precision ones (16 half ulp) enough to clear their rounding. */
#define PHONGCL_SHADOW_OFFSET_FLOAT 0x1p-20f
#define PHONGCL_SHADOW_OFFSET_HALF 0x1p-7f

/* What a link leads to: its kind in the low PHONGCL_BVH_KIND_BITS bits, and for a run of primitives
 * (a leaf) or planes the number of them above. An empty child (beside a root that is one leaf) is a
 * run of no triangles, with an empty box. */
enum { BVH_INNER = 0, BVH_TRIANGLES = 1, BVH_SPHERES = 2, BVH_PLANES = 3 };
#define PHONGCL_SMALL_TRIANGLE 0xffffffffu
#define PHONGCL_SMALL_TRIANGLE_REACH 4096.0
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

/* A triangle: its three corners (rows), counter-clockwise seen from the front, and in column 3 the
 * point f of its plane nearest the eye, worked out in double: the plane is x.f = f.f (a plane
 * within 2^-64 of the eye moved to 2^-64 along its normal; f = 0 for a degenerate triangle). A
 * triangle whose corners all lie within PHONGCL_SMALL_TRIANGLE_REACH of the eye has instead
 * PHONGCL_SMALL_TRIANGLE's bits in row[0][3] (a NaN no plane has): the kernel takes the quicker
 * Moller-Trumbore test for it, which float holds there (kernels/bvh.h).
 * A sphere in its own space under any affine map (an ellipsoid in the world): the map from an
 * eye-relative point x to the unit sphere's space, u = A x + b, row i of A in row[i][0..2] and b_i
 * in row[i][3]; the surface is |u| = 1. */
typedef struct {
  float row[3][4];
} ShadowPrimitive;

/* A primitive's box, parallel to the primitives (rounded outwards like the nodes'): what tiled
 * culling tests each primitive of a leaf with. */
typedef struct {
  float lo[3];
  float hi[3];
} ShadowBounds;

/* An unbounded plane: the points x with dot(normal, x) == offset; normal of unit length. */
typedef struct {
  float normal[3];
  float offset;
} ShadowPlane;

/* Tiled shadow culling: per screen tile and shadow-casting light, the runs of primitives (of one
 * leaf) and the planes that can block any of the tile's rays toward that light, as links
 * (first, kind | count << PHONGCL_BVH_KIND_BITS). A tile and light with more than
 * PHONGCL_SHADOW_CANDIDATE_LIMIT runs get none and a count of PHONGCL_SHADOW_TRAVERSE: its rays
 * traverse the whole BVH instead. */
typedef struct {
  unsigned int first;
  unsigned int kind_count;
} ShadowCandidate;
#define PHONGCL_SHADOW_CANDIDATE_LIMIT 48
#define PHONGCL_SHADOW_TRAVERSE 0xffffffffu

/* Culling runs in two levels (kernels/shadow_cull.cl): tiles of PHONGCL_SHADOW_COARSE_RATIO^2 tiles
 * walk the BVH, with a longer list allowed, and each tile filters its parent's list. */
#define PHONGCL_SHADOW_COARSE_RATIO 4
#define PHONGCL_SHADOW_COARSE_LIMIT 256

/* Where a culling level takes its candidates from: the BVH (ratio 0) or the level above, whose tiles
 * are ratio x ratio of this level's. */
typedef struct {
  unsigned int ratio;
  unsigned int tiles_x;        /* this level's tiles per row */
  unsigned int parent_tiles_x, parent_tiles;
} CullLevel;

/* A shadow-casting light as the culling sees it: a point or spot light's position, or a
 * directional light's unit l (toward the light), eye-relative; a light whose rays end anywhere on
 * it (a soft area light) has the half size of its bounding box around `where`, else 0. */
typedef struct {
  float where[3];
  unsigned int directional;
  float half_extent[3];
  float padding;
} ShadowLight;

/* Screen-space shadows march across the frame's depth plane (the view depth of each pixel's surface,
 * +Inf where there is none), so they need the camera that made the G-buffer: an eye-relative point X
 * lands at pixel coordinates (centre_x + scale_x * X.right / X.forward, centre_y - scale_y * X.up /
 * X.forward) of the plane (its pixel (0, 0) spans [0, 1) x [0, 1); rows run down). */
typedef struct {
  float forward[4], right[4], up[4]; /* unit; w unused */
  float scale_x, scale_y;            /* pixels per unit of the image plane at depth 1 */
  float centre_x, centre_y;          /* where the optical axis meets the plane */
  unsigned int width, height;        /* the depth plane's pixels */
  float near_depth, far_depth;       /* the nearest and farthest surfaces' depths: the march stays between */
  unsigned int steps;                /* samples along each ray */
  float thickness;                   /* a surface hides what lies up to this far behind it (view depth, world units) */
  unsigned int padding[2];
} ScreenMarch;

/* The shading kernel's shadow scalars (kernels/phong.cl): the geometry's counts, the self-intersection
 * offset's scale (PHONGCL_SHADOW_OFFSET_FLOAT or _HALF) and |eye|_inf (kernels/shadow.h), and the
 * screen-space march's camera. */
typedef struct {
  ScreenMarch march;
  unsigned int node_count, plane_count;
  float offset_scale, eye_extent;
} ShadowFrame;

#endif
