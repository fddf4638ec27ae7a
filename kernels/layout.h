/* What the host and the kernels must agree on, written once for both languages (ISPC deferred.h
 * style). Fixed-width fields and explicit padding: no float3 in shared structs (cl_float3 is 16 bytes).
 * The host static-asserts sizes and offsets (host/shading/device_layout.h). */
#ifndef PHONGCL_LAYOUT_H
#define PHONGCL_LAYOUT_H

#include "shadow_layout.h"

/* float and int are 32 bits on both sides (OpenCL C requires it; the host static-asserts the sizes). */
typedef float layout_float;
typedef int layout_int;
typedef unsigned int layout_uint;

/* Lights per block of the kernel's compensated sum (phong.cl's light loops). */
#define PHONGCL_LIGHT_BLOCK 16
/* Up to this many lights of a type, the count is a compile-time constant and the loop unrolls: one
 * block, so an unrolled loop needs no compensation between blocks. */
#define PHONGCL_UNROLL_LIGHT_LIMIT PHONGCL_LIGHT_BLOCK

/* The kernel's output planes: R G B A, and with WRITE_TERMS the terms ambient, diffuse, specular RGB. */
#define PHONGCL_OUTPUT_PLANES 4
#define PHONGCL_TERM_PLANES 9

/* The screen tiles of tiled light culling. A work-item belongs to the tile of its first pixel, and
 * the tile's bounds cover every lane of its work-items (the last one of a row may reach into the
 * next tile), so one light list serves all of a work-item's pixels. */
typedef struct {
  unsigned int image_width; /* pixels per row */
  unsigned int tile_size;   /* tiles are tile_size pixels wide */
  unsigned int tile_rows;   /* and tile_rows tall */
  unsigned int tiles_x;     /* tiles per row */
  unsigned int first_pixel; /* the frame pixel of this launch's slot 0 */
} TileGrid;

/* phong_shade reads its tables from a few blocks, one buffer each (ISPC's deferred example passes
 * one header and offsets into one block): these say where each table starts in its block, in 4-byte
 * words. A new table is a field here and a line where the host packs the block, not a parameter. */

/* The scene's block (pack.h): colours scaled by 2^-radiance_exponent. Per light, `links` holds
 * LIGHT_LINKING words (point lights', then directional lights'); shadow_casters and light_groups a
 * word (point lights', then directional lights', then area lights'). */
typedef struct {
  layout_uint materials;          /* MaterialRecord per material */
  layout_uint point_lights;       /* PointLight: point and spot lights */
  layout_uint point_shapes;       /* LightShape, parallel to point_lights */
  layout_uint links;              /* LinkWord: light linking masks */
  layout_uint directional_lights; /* DirectionalLight */
  layout_uint area_lights;        /* AreaLightRecord: rects and disks */
  layout_uint shadow_casters;     /* SHADOWS: 1 + the light's place among the casters where it casts shadows, else 0 */
  layout_uint light_groups;       /* LIGHT_GROUPS: the light's group, LIGHT_GROUPS for none */
  layout_uint soft_lights;        /* SOFT_SHADOWS: SoftLight per light, in the casters' order */
  layout_uint environment;        /* ENVIRONMENT: one EnvironmentRecord */
  layout_uint environment_texels; /* ENVIRONMENT: its irradiance map, RGB floats row by row from the top */
  layout_uint environment_suns;   /* ENVIRONMENT: EnvironmentSun per bright cell taken out of the map */
  layout_uint environment_lobes;  /* ENVIRONMENT and SPECULAR: EnvironmentLobe per material */
} SceneTables;

/* Tiled culling's block (cull.cl): tile t's point lights are lights[offsets[t] ...], counts[t] of
 * them, the first holding[t] holding all of the tile in their bounds. */
typedef struct {
  layout_uint offsets, counts, holding, lights;
} TileListTables;

/* The shadow geometry's block (shadow_layout.h): the BVH's nodes, its primitives and their bounds,
 * the unbounded planes, and for screen-space shadows the frame's depth plane (floats). */
typedef struct {
  layout_uint nodes, primitives, bounds, planes, depth;
} ShadowGeometryTables;

/* Tiled shadow culling's block (shadow_cull.cl): pair caster * tiles + tile holds counts[pair]
 * candidates from candidates[offsets[pair]], or PHONGCL_SHADOW_TRAVERSE. */
typedef struct {
  layout_uint counts, offsets, candidates;
} ShadowListTables;

/* The per-frame scalars, one kernel argument (by value) rather than a row of floats that compiles
 * with two of them swapped. Colours are scaled by 2^-radiance_exponent so that sums of HDR values
 * near float's limits cannot overflow early; the kernel multiplies by a * b = 2^e at the end. */
typedef struct {
  layout_float ambient[4];                        /* La, rgb scaled; a unused */
  layout_float background[4];                     /* rgb, not scaled; a unused */
  layout_float radiance_scale_a, radiance_scale_b; /* two power-of-two factors, each a normal float */
  layout_int point_count, directional_count;      /* entries in the light tables */
  layout_uint plane_stride;                       /* values per plane in every buffer, a multiple of PHONGCL_LANES */
  layout_int area_count;                          /* entries in the area light table */
  layout_uint shadow_tiles;                       /* tiled shadow culling's tiles; 0 without its lists */
  layout_uint first_pixel;                        /* the frame pixel of this launch's slot 0 (soft shadows' sequence) */
  SceneTables scene;                              /* where the blocks' tables start */
  TileListTables tile_lists;
  ShadowGeometryTables shadow_geometry;
  ShadowListTables shadow_lists;
  TileGrid grid;                                  /* TILED_CULLING: the light lists' tiles */
  TileGrid shadow_grid;                           /* tiled shadow culling's tiles */
  ShadowFrame shadow;                             /* SHADOWS: the geometry's counts, the ray offsets, the march */
} FrameScalars;

/* A point light. position is relative to the eye: the host rebases in double so that a scene far
 * from the origin loses nothing when converted to float. position_rest is what the float rounding
 * of position lost (position + position_rest is the double): with the G-buffer's rest planes the
 * kernel forms L - P to float precision where a light is 1e-8 of its distance from a surface
 * (phong.cl, light_offset()). color is scaled by 2^-radiance_exponent. */
typedef struct {
  layout_float position[4];      /* xyz, w unused */
  layout_float color[4];         /* rgb, a unused */
  layout_float position_rest[4]; /* xyz, w unused */
} PointLight;

/* The largest falloff power (cubic); the kernel unrolls its powers up to it. */
#define PHONGCL_MAX_FALLOFF 3

/* How a point or spot light's F = falloff(d) * window(d) * cone(l) is shaped (docs/shading.md
 * "The formula"), parallel to the point lights; only scenes with falloff, ranges or spots read it.
 * The cone is given by versines, 1 - cos, computed in double: a cone of 1e-3 degrees has
 * cos(A/2) = 1 - 4e-11, which is 1 in float. A point light has versine_inner = versine_outer = 3
 * (every direction is inside its "cone": 1 - c <= 2); a hard-edged spot has versine_outer =
 * versine_inner and inverse_cone_width 0. */
typedef struct {
  layout_float axis[4];             /* spot: unit direction it points; w unused */
  layout_float inverse_range;       /* 1 / R, 0 without a range */
  layout_float versine_inner;       /* 1 - cos(A/2) */
  layout_float versine_outer;       /* 1 - cos(A/2 + P) */
  layout_float inverse_cone_width;  /* 1 / (versine_outer - versine_inner), 0 for a hard edge */
  int falloff;                      /* the power k of 1/d^k: 0 to PHONGCL_MAX_FALLOFF */
  layout_float cosine_power;        /* spot: p of max(0, dot(-l, axis))^p; 0 for none and point lights */
  int padding[2];
} LightShape;

/* Light linking: bit m of word m / 32 of a light's mask is set when it lights material m. Each light
 * (point lights first, then directional) has LINK_WORDS words. */
typedef unsigned int LinkWord;

/* What a point or spot light can reach, for tiled culling: a sphere that holds it (its range, or
 * for a spot the cone bounded by it; radius < 0: no range, the light reaches every tile) and, for a
 * spot narrower than a hemisphere, its cone: apex, unit axis, and the cosine and sine of the outer
 * half angle, widened on the host against rounding (cone_cos <= 0: no cone to test). */
typedef struct {
  layout_float center[3]; /* relative to the eye */
  layout_float radius;
  layout_float apex[3]; /* relative to the eye */
  layout_float cone_cos;
  layout_float axis[3];
  layout_float cone_sin;
  unsigned int distance_bins; /* the distance bins its sphere spans; every bin without a range */
  unsigned int padding[3];
} LightBounds;



/* Distance bins, for culling in depth as well as across the screen (Harada's 2.5D culling, with bins
 * fixed in distance rather than per tile): a distance d from the eye is in bin (the float bits of
 * d^2 >> PHONGCL_DISTANCE_BIN_SHIFT) mod 32, four bins per doubling of d^2. A tile sets the bit of
 * each of its shaded positions' bins, a light the bits of every distance its sphere spans (widened
 * by a bin each way against rounding); a light whose bits miss the tile's reaches none of its
 * pixels. Distances further apart than a factor of 16 share bins: that keeps lights, never drops one. */
#define PHONGCL_DISTANCE_BIN_SHIFT 21

/* A culling tile's bounds: the box of its shaded positions (eye-relative, as packed), the distance
 * bins they fall in and how many shaded pixels it holds; an empty tile has shaded = 0, an empty box
 * (lo > hi) and no bins. */
typedef struct {
  layout_float lo[3];
  unsigned int shaded;
  layout_float hi[3];
  unsigned int distance_bins;
} TileBox;

/* The culling tests a block of up to eight boxes at once (cull.cl's keep_box_lights), given as eight
 * box indices; a block at the grid's edge, or of fewer boxes, has PHONGCL_NO_BOX in the slots past it. */
#define PHONGCL_NO_BOX 0xffffffffu

/* A directional light. to_light is the unit vector l = -normalize(direction), computed in double. */
typedef struct {
  layout_float to_light[4]; /* xyz, w unused */
  layout_float color[4];    /* rgb, a unused */
} DirectionalLight;

/* An area light (kernels/area_light.h): a one-sided Lambertian rect or disk. center is relative to
 * the eye (rebased in double, like a point light's position). A rect spans center +- axis_u +-
 * axis_v, with axis_u x axis_v along normal; a disk has radius |axis_u| = |axis_v| in their plane.
 * color (radiance, 1/pi folded in) is scaled by 2^-radiance_exponent. */
enum { AREA_RECT = 0, AREA_DISK = 1 };
typedef struct {
  layout_float center[4]; /* xyz, w unused */
  layout_float normal[4]; /* unit normal of the emitting side; w unused */
  layout_float axis_u[4]; /* rect: half the width; disk: the radius along u; w unused */
  layout_float axis_v[4]; /* rect: half the height; disk: the radius along v; w unused */
  layout_float color[4];  /* rgb, a unused */
  layout_int shape;       /* AREA_RECT or AREA_DISK */
  layout_float inverse_range; /* 1 / R, 0 without a range */
  layout_float area;      /* of the emitter */
  layout_float padding;
} AreaLightRecord;

/* A light's soft shadow (soft_shadow.h): its rays per pixel (1: one ray, the hard shadow) and its
 * size: a sphere light's radius, a sun's tan(half its angular diameter), 0 for an area light (its
 * record holds its shape). */
typedef struct {
  layout_uint rays;
  layout_float size;
} SoftLight;

/* The environment light (kernels/environment.h): its irradiance map (E / pi, so that kd times it is the
 * diffuse light) is width x height texels, equirectangular in the map's frame. to_map's rows take an
 * eye-relative direction into that frame (the world's orientation, then the light's rotation about
 * +Z). scale is the strength times 2^-radiance_exponent. The map's brightest cells (a sun) are taken
 * out of it and come as sun_count EnvironmentSuns: directional lights, each with a shadow ray. The
 * radiance without them (sky_width x sky_height texels after the irradiance's) is what a blocked
 * visibility ray takes away. */
typedef struct {
  layout_float to_map[12]; /* three rows of xyz, w unused */
  layout_float scale;
  layout_int width, height;
  layout_uint rays;        /* ENVIRONMENT_SHADOWS: visibility rays per pixel */
  layout_int sun_count;
  layout_int sky_width, sky_height; /* ENVIRONMENT_SHADOWS: the radiance without the suns, */
  layout_uint sky_offset;           /* at this float offset in the texels */
} EnvironmentRecord;

/* A bright cell of the environment as a directional light: unit direction toward it (eye frame) and
 * its E / pi per unit cosine (unscaled: the record's scale multiplies). */
typedef struct {
  layout_float direction[4]; /* xyz, w unused */
  layout_float color[4];     /* rgb, a unused */
} EnvironmentSun;

/* A material's specular lobe under the environment (kernels/environment_specular.h): its prefiltered
 * map, width x height RGB texels at float `offset` of the environment's texels, the lobe-weighted
 * mean radiance about r = 2(n.v)n - v. The Phong family multiplies it by `amplitude` (the classic
 * lobe's integral over pi, 2 / (p + 1) for the Phong exponent p), and by max(0, n.r) where
 * `takes_cosine` (the normalised models' n.l); a `split_sum` lobe (Principled) by the BRDF table's
 * cspec0 A + B instead (kernels/environment_brdf.h). With ENVIRONMENT_SHADOWS it is multiplied by the
 * sky-weighted share of rays spread about r by `spread`, the lobe's angular width (radians), that are free. A Blinn-Phong lobe (`half_vector`) is also multiplied by n.v: its integral over
 * w is 4 v.h times that over h, v.h = n.v at its peak. */
typedef struct {
  layout_uint offset;
  layout_int width, height;
  layout_float amplitude;
  layout_int takes_cosine, split_sum;
  layout_float spread;
  layout_int half_vector;
} EnvironmentLobe;

/* One entry of the scene's material table. */
typedef struct {
  layout_float ka[4], kd[4], ks[4]; /* rgb, a unused */
  layout_float shininess;
  layout_float specular_model; /* the model's number (specular.h), a float so the lanes' selects read it as the others */
  layout_float roughness, ior; /* the Principled model's (principled.h); 0 for the others */
  /* The Principled v2 model's (principled.h), 0 for the others: */
  layout_float metal_f0[4];       /* the F82-tint metal's F0 (rgb), a: metallic */
  layout_float metal_b[4];        /* its B term (rgb), a: 1 where the dielectric layer is (its index is not 1) */
  layout_float fresnel_average;   /* the dielectric lobe's hemispherical mean Fresnel factor (fresnel_dielectric_Fss) */
  layout_float diffuse_roughness; /* Oren-Nayar's sigma in [0, 1], 0 (Lambert) below Cycles' 1e-5 */
  layout_float unused[2];
} MaterialRecord;

/* Float offsets of MaterialRecord's fields, for the kernel's per-lane gathers. */
enum {
  MATERIAL_KA = 0, MATERIAL_KD = 4, MATERIAL_KS = 8, MATERIAL_SHININESS = 12, MATERIAL_SPECULAR_MODEL = 13,
  MATERIAL_ROUGHNESS = 14, MATERIAL_IOR = 15, MATERIAL_METAL_F0 = 16, MATERIAL_METALLIC = 19, MATERIAL_METAL_B = 20,
  MATERIAL_DIELECTRIC_LAYER = 23, MATERIAL_FRESNEL_AVERAGE = 24, MATERIAL_DIFFUSE_ROUGHNESS = 25
};

/* The G-buffer lives in one device buffer of planes (structure of arrays: kernels over plain float
 * arrays vectorise, float3 code does not). Plane k of a tile starts at k * plane_stride. The
 * per-pixel material planes follow the geometry planes, in this order, only if present. */
enum {
  PLANE_PX, PLANE_PY, PLANE_PZ, /* position - eye, rounded to float (its rest: material.h's PLANE_REST) */
  PLANE_NX, PLANE_NY, PLANE_NZ, /* normal, any length */
  PLANE_GEOMETRY_COUNT
};

/* Material index value that marks a pixel as background (not shaded). */
#define PHONGCL_BACKGROUND (-1)

#endif
