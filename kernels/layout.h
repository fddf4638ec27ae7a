/* What the host and the kernels must agree on, written once for both languages (ISPC deferred.h
 * style). Fixed-width fields and explicit padding: no float3 in shared structs (cl_float3 is 16 bytes).
 * The host static-asserts sizes and offsets (host/shading/device_layout.h). */
#ifndef PHONGCL_LAYOUT_H
#define PHONGCL_LAYOUT_H

/* float is 32-bit IEEE on both sides (OpenCL C requires it; the host static-asserts the sizes). */
typedef float layout_float;

/* A point light. position is relative to the eye: the host rebases in double so that a scene far
 * from the origin loses nothing when converted to float. color is scaled by 2^-radiance_exponent. */
typedef struct {
  layout_float position[4]; /* xyz, w unused */
  layout_float color[4];    /* rgb, a unused */
} PointLight;

/* A directional light. to_light is the unit vector l = -normalize(direction), computed in double. */
typedef struct {
  layout_float to_light[4]; /* xyz, w unused */
  layout_float color[4];    /* rgb, a unused */
} DirectionalLight;

/* One entry of the scene's material table. */
typedef struct {
  layout_float ka[4], kd[4], ks[4]; /* rgb, a unused */
  layout_float shininess;
  layout_float padding[3];
} MaterialRecord;

/* Float offsets of MaterialRecord's fields, for the kernel's per-lane gathers. */
enum { MATERIAL_KA = 0, MATERIAL_KD = 4, MATERIAL_KS = 8, MATERIAL_SHININESS = 12 };

/* The G-buffer lives in one device buffer of planes (structure of arrays: kernels over plain float
 * arrays vectorise, float3 code does not). Plane k of a tile starts at k * plane_stride. The
 * per-pixel material planes follow the geometry planes, in this order, only if present. */
enum {
  PLANE_PX, PLANE_PY, PLANE_PZ, /* position - eye */
  PLANE_NX, PLANE_NY, PLANE_NZ, /* normal, any length */
  PLANE_GEOMETRY_COUNT
};

/* Material index value that marks a pixel as background (not shaded). */
#define PHONGCL_BACKGROUND (-1)

#endif
