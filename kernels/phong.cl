/* Deferred Phong shading; each work-item shades PHONGCL_LANES consecutive pixels (phong_math.h):
 *   L_o = ka*La + sum_i Li * [ kd*max(0, n.l_i) + ks*max(0, v.r_i)^q ],  r = 2(n.l)n - l
 * Only what the scene needs is compiled in. The host (host/shading/recipe.cpp) writes the options;
 * `phongcl shade --explain` prints them:
 *   PHONGCL_LANES=n                    pixels per work-item (a CPU's preferred float width, 1 on GPUs)
 *   POINT_LIGHTS, DIRECTIONAL_LIGHTS   light types present
 *   POINT_COUNT=n, DIRECTIONAL_COUNT=n compile-time light counts (loops unroll), else run-time
 *   SPECULAR, AMBIENT                  terms present
 *   SINGLE_MATERIAL                    every shaded pixel uses materials[0]: no per-pixel fetch
 *   MATERIAL_COUNT=n                   a table of n <= PHONGCL_LANES materials: selects, no gather
 *   PLANE_KA=k PLANE_KD=k PLANE_KS=k PLANE_Q=k   per-pixel material planes and where they are
 *   UNIFORM_SPACE=__constant|__global  where the light and material tables live
 *   HALF_STORAGE                       G-buffer planes stored as half (vload_half)
 *   PHONGCL_DOUBLE                     fp64 arithmetic (see phong_math.h)
 *   PHONGCL_FAST                       built with -cl-fast-relaxed-math (see unscale)
 *   WRITE_TERMS                        also write ambient, diffuse, specular separately (AOVs)
 *   FALLOFF, FALLOFF_MIXED, RANGE_WINDOW, SPOT_LIGHTS, LIGHT_LINKING   light shapes (light_shape.h)
 *   TILED_CULLING                      point and spot lights from the work-item's tile list (cull.cl)
 * Every buffer is planar with frame.plane_stride values per plane, a multiple of PHONGCL_LANES (the
 * host pads each tile with background pixels).
 */
#include "layout.h"
#include "light_shape.h"
#include "phong_math.h"
#include "tiles.h"

#ifdef HALF_STORAGE
#define STORAGE half
#define LOAD_PLANE(plane) TO_REALV(VLOAD_HALF(group, planes + (size_t)(plane) * plane_stride))
#else
#define STORAGE float
#define LOAD_PLANE(plane) TO_REALV(VLOAD_FLOAT(group, planes + (size_t)(plane) * plane_stride))
#endif
#define LOAD_PLANE3(plane) make_vec3(LOAD_PLANE(plane), LOAD_PLANE((plane) + 1), LOAD_PLANE((plane) + 2))

#if defined(TILED_CULLING)
#define POINT_LOOP_COUNT tile_count
#define POINT_LIGHT_INDEX(k) tile_lights[tile_first + (k)]
#elif defined(POINT_COUNT)
#define POINT_LOOP_COUNT POINT_COUNT
#else
#define POINT_LOOP_COUNT frame.point_count
#endif
#ifdef DIRECTIONAL_COUNT
#define DIRECTIONAL_LOOP_COUNT DIRECTIONAL_COUNT
#else
#define DIRECTIONAL_LOOP_COUNT frame.directional_count
#endif
#ifndef POINT_LIGHT_INDEX
#define POINT_LIGHT_INDEX(k) (k)
#endif

/* Sums of Li*max(0, n.l) and Li*spec over the lights; the material multiplies once at the end. */
typedef struct {
  vec3 diffuse, specular;
} LightSums;

/* sum += value, with the rounding error carried in compensation (Kahan). */
inline void kahan_add(realv* sum, realv* compensation, realv value) {
  const realv corrected = value - *compensation;
  const realv next = *sum + corrected;
#ifdef WEIGHT_CAN_OVERFLOW
  *compensation = SELECT(next - next == 0, (next - *sum) - corrected, 0); /* Inf - Inf: keep +Inf, not NaN */
#else
  *compensation = (next - *sum) - corrected;
#endif
  *sum = next;
}

inline void add_block(LightSums* sums, LightSums* compensation, const LightSums* block) {
  kahan_add(&sums->diffuse.x, &compensation->diffuse.x, block->diffuse.x);
  kahan_add(&sums->diffuse.y, &compensation->diffuse.y, block->diffuse.y);
  kahan_add(&sums->diffuse.z, &compensation->diffuse.z, block->diffuse.z);
  kahan_add(&sums->specular.x, &compensation->specular.x, block->specular.x);
  kahan_add(&sums->specular.y, &compensation->specular.y, block->specular.y);
  kahan_add(&sums->specular.z, &compensation->specular.z, block->specular.z);
}

/* Adds one light's contribution, times its weight F (light_shape.h; 1 without shapes or linking,
 * which the compiler folds away). `toward` points at the light and `inverse` is 1 / |toward| (1 for
 * a directional light's unit vector), so l = toward * inverse. Nothing here waits for that square
 * root before it must: the loop is latency-bound, and a point light's chain was 50% longer. */
inline void add_light(LightSums* sums, vec3 n, vec3 v, vec3 toward, realv inverse, const UNIFORM_SPACE float* color,
                      realv shininess, realv weight) {
  const realv n_dot = dot3(n, toward);
  const realv ndl = n_dot * inverse;
  const realv lit_ndl = SELECT(ndl > 0, ndl * weight, 0); /* back-facing or grazing: nothing from this light */
  sums->diffuse.x += NONNEGATIVE_TIMES(color[0], lit_ndl);
  sums->diffuse.y += NONNEGATIVE_TIMES(color[1], lit_ndl);
  sums->diffuse.z += NONNEGATIVE_TIMES(color[2], lit_ndl);
#ifdef SPECULAR
  /* r = 2(n.l)n - l = -inverse * w, w = toward - 2(n.toward)n with one rounding per component.
   * Near the highlight peak v - r = v + inverse * w has one rounding too (fma), so w's rounding is
   * all the error in 1 - v.r, which the specular power multiplies by q. */
  const realv two_n_dot = 2 * n_dot;
  const vec3 w = make_vec3(fma(-two_n_dot, n.x, toward.x), fma(-two_n_dot, n.y, toward.y), fma(-two_n_dot, n.z, toward.z));
  const vec3 v_minus_r = make_vec3(fma(inverse, w.x, v.x), fma(inverse, w.y, v.y), fma(inverse, w.z, v.z));
  const realv cos_vr = -inverse * dot3(v, w);
  const realv spec = specular_power(cos_vr, (real)0.5 * dot3(v_minus_r, v_minus_r), shininess);
  const realv lit_spec = SELECT(ndl > 0, NONNEGATIVE_TIMES(spec, weight), 0);
  sums->specular.x += NONNEGATIVE_TIMES(color[0], lit_spec);
  sums->specular.y += NONNEGATIVE_TIMES(color[1], lit_spec);
  sums->specular.z += NONNEGATIVE_TIMES(color[2], lit_spec);
#endif
}

/* One field of a material record; `field` is a float offset within MaterialRecord (layout.h),
 * read through the named array it falls in (indexing past ka[4] is undefined behaviour; `field` is
 * a constant at every call, so the choice folds away). Through a function returning a private
 * value: clang 15 (PoCL 3.1) crashes on a vector literal cast straight from a __constant lvalue. */
inline real material_scalar(UNIFORM_SPACE const MaterialRecord* record, int field) {
  return field < MATERIAL_KD ? record->ka[field - MATERIAL_KA]
         : field < MATERIAL_KS ? record->kd[field - MATERIAL_KD]
         : field < MATERIAL_SHININESS ? record->ks[field - MATERIAL_KS]
                                      : record->shininess;
}

#if defined(MATERIAL_COUNT)
/* A table of MATERIAL_COUNT <= PHONGCL_LANES entries: each lane's field is picked by comparing its
 * index with every entry (uniform loads and selects). PoCL lowers per-lane gathers, and shuffles
 * with a variable mask, through per-work-item private memory: 7 of the 11 ms of a 1080p frame
 * without lights. Background lanes (index -1) get entry 0. */
inline realv select_field(UNIFORM_SPACE const MaterialRecord* table, intv index, int field) {
  const realv lane_index = TO_REALV(index);
  realv value = (realv)material_scalar(&table[0], field);
#pragma unroll /* so the index comparisons are shared by every field */
  for (int m = 1; m < MATERIAL_COUNT; ++m) value = SELECT(lane_index == (real)m, material_scalar(&table[m], field), value);
  return value;
}
#define MATERIAL_FIELD(field) select_field(materials, index, field)
#elif !defined(SINGLE_MATERIAL) && PHONGCL_LANES > 1
/* One field of each lane's material record: a gather through private memory (no dynamic lane
 * indexing in OpenCL C). */
inline realv gather_field(UNIFORM_SPACE const MaterialRecord* table, const int* index, int field) {
  real values[PHONGCL_LANES];
  for (int k = 0; k < PHONGCL_LANES; ++k) values[k] = material_scalar(&table[index[k]], field);
  return PHONGCL_XCAT(vload, PHONGCL_LANES)(0, values);
}
#define MATERIAL_FIELD(field) gather_field(materials, lane_material, field)
#else
/* One material for the whole work-item: a uniform load. */
#ifdef SINGLE_MATERIAL
#define MATERIAL_RECORD (&materials[0])
#else
#define MATERIAL_RECORD (&materials[lane_material[0]])
#endif
#define MATERIAL_FIELD(field) ((realv)material_scalar(MATERIAL_RECORD, field))
#endif
#define MATERIAL_FIELD3(field) make_vec3(MATERIAL_FIELD(field), MATERIAL_FIELD((field) + 1), MATERIAL_FIELD((field) + 2))

/* Undoes the host's radiance scaling by 2^e = a * b (two power-of-two factors, each a normal
 * float): (value * a) * b is exact up to one rounding, and overflows only when the exact result
 * does. Under -cl-fast-relaxed-math the compiler may reassociate that into value * (a * b), and
 * a * b = 2^128 overflows (3e38 lights gave +Inf for a finite 1.5e38, and 0 * Inf = NaN in dark
 * pixels), so the fast variant uses ldexp, which no flag rewrites. */
#ifdef PHONGCL_FAST
/* A vector exponent rather than ldexp(floatn, int): Oclgrind 21.10 gets that overload's lanes wrong. */
inline floatv unscale(realv value, float a, float b) { return TO_FLOATV(ldexp(value, (intv)(ilogb(a) + ilogb(b)))); }
#else
inline floatv unscale(realv value, float a, float b) { return TO_FLOATV(value * a * b); }
#endif

/* The image planes are written once and not read again here: with Clang (PoCL) they are streamed
 * past the caches, so no line is first read for ownership (16 of the 20 bytes a pixel costs at 0
 * lights). Planes start at multiples of PHONGCL_LANES floats, so the floatv is aligned. */
#if defined(__clang__) && PHONGCL_LANES > 1
#define STORE_OUTPUT(v, i, p) __builtin_nontemporal_store((v), (__global floatv*)(p) + (i))
#else
#define STORE_OUTPUT(v, i, p) VSTORE_FLOAT(v, i, p)
#endif

inline void store3(vec3 value, float a, float b, size_t group, __global float* restrict out, uint plane_stride) {
  VSTORE_FLOAT(unscale(value.x, a, b), group, out);
  VSTORE_FLOAT(unscale(value.y, a, b), group, out + plane_stride);
  VSTORE_FLOAT(unscale(value.z, a, b), group, out + 2 * (size_t)plane_stride);
}

__kernel void phong_shade(
    /* G-buffer tile: planes (see layout.h), positions relative to the eye */
    __global const STORAGE* restrict planes,
    __global const int* restrict material_index,
    /* scene; colours scaled by 2^-radiance_exponent, undone by the two scale factors */
    UNIFORM_SPACE const MaterialRecord* restrict materials,
    UNIFORM_SPACE const PointLight* restrict point_lights,
    UNIFORM_SPACE const DirectionalLight* restrict directional_lights,
    /* ambient, background, radiance scales, light counts, plane stride (layout.h) */
    const FrameScalars frame,
    /* output planes (PHONGCL_OUTPUT_PLANES): R G B A; with WRITE_TERMS also the terms (PHONGCL_TERM_PLANES) */
    __global float* restrict out_rgba, __global float* restrict out_terms,
    /* light shapes and linking masks (light_shape.h), read only when compiled in */
    UNIFORM_SPACE const LightShape* restrict point_shapes, UNIFORM_SPACE const LinkWord* restrict links,
    /* tiled culling (cull.cl): tile t's point lights are tile_lights[tile_offsets[t] ...] */
    __global const uint* restrict tile_offsets, __global const uint* restrict tile_counts,
    __global const uint* restrict tile_lights, const TileGrid grid) {
  const size_t group = get_global_id(0);
  const uint plane_stride = frame.plane_stride;
  const float radiance_scale_a = frame.radiance_scale_a, radiance_scale_b = frame.radiance_scale_b;
#ifdef TILED_CULLING
  const uint tile = tile_of_pixel(grid, grid.first_pixel + (uint)(group * PHONGCL_LANES));
  const uint tile_first = tile_offsets[tile];
  const int tile_count = (int)tile_counts[tile];
#endif
  const intv index = VLOAD_INT(group, material_index);
  const intv background = index == PHONGCL_BACKGROUND;
  /* Background lanes read material 0 and are replaced by the background colour at the end. */
#if !defined(SINGLE_MATERIAL) && !defined(MATERIAL_COUNT)
  int lane_material[PHONGCL_LANES];
  for (int k = 0; k < PHONGCL_LANES; ++k) lane_material[k] = max(material_index[group * PHONGCL_LANES + k], 0);
#endif
#ifdef PLANE_Q
  const realv shininess = LOAD_PLANE(PLANE_Q);
#else
  const realv shininess = MATERIAL_FIELD(MATERIAL_SHININESS);
#endif

  /* The eye is the origin: v = normalize(E - P) = normalize(-P). */
  const vec3 p = LOAD_PLANE3(PLANE_PX);
  const vec3 n = unit_or_zero(LOAD_PLANE3(PLANE_NX));
  const vec3 v = unit_or_zero(make_vec3(-p.x, -p.y, -p.z));

  const realv zero = 0;
  /* Lights are summed in blocks of PHONGCL_LIGHT_BLOCK in plain float, and the block sums compensated
   * (Kahan): the error stays a few ulp plus one block's however many lights there are (10,000 lights,
   * one of 1 then 9,999 of 3e-8: plain float 3.0e-4 relative, blocked Kahan 4.5e-7). Unrolled
   * counts up to 16 are one block. -cl-fast-relaxed-math may fold the compensation away (fast). */
  const LightSums no_light = {{zero, zero, zero}, {zero, zero, zero}};
  LightSums sums = no_light, compensation = no_light;
#ifdef POINT_LIGHTS
  for (int first = 0; first < POINT_LOOP_COUNT; first += PHONGCL_LIGHT_BLOCK) {
    LightSums block = no_light;
    for (int k = first; k < min(first + PHONGCL_LIGHT_BLOCK, POINT_LOOP_COUNT); ++k) {
      const int light_index = POINT_LIGHT_INDEX(k);
      UNIFORM_SPACE const PointLight* light = &point_lights[light_index];
      const vec3 position = make_vec3(light->position[0], light->position[1], light->position[2]);
      vec3 toward = sub3(position, p);
#if defined(TILED_CULLING) && defined(RANGE_WINDOW)
      if (beyond_range_in_every_lane(&point_shapes[light_index], toward)) continue;
#endif
#ifdef NEEDS_DISTANCE
      realv distance, inverse_distance;
      const realv inverse = distance_in_range(&toward, &distance, &inverse_distance);
#else
      const realv inverse = inverse_length_in_range(&toward);
#endif
#if defined(TILED_CULLING) && defined(SPOT_LIGHTS)
      if (outside_cone_in_every_lane(&point_shapes[light_index], toward, inverse)) continue;
#endif
#ifdef POINT_SHAPES
#ifndef NEEDS_DISTANCE
      const realv distance = 0, inverse_distance = 0; /* spots alone read neither */
#endif
      const realv weight = shape_weight(&point_shapes[light_index], toward, inverse, distance, inverse_distance,
                                        LINK_GATE(light_index));
#else
      const realv weight = LINK_GATE(light_index);
#endif
      add_light(&block, n, v, toward, inverse, light->color, shininess, weight);
    }
    add_block(&sums, &compensation, &block);
  }
#endif
#ifdef DIRECTIONAL_LIGHTS
  for (int first = 0; first < DIRECTIONAL_LOOP_COUNT; first += PHONGCL_LIGHT_BLOCK) {
    LightSums block = no_light;
    for (int k = first; k < min(first + PHONGCL_LIGHT_BLOCK, DIRECTIONAL_LOOP_COUNT); ++k) {
      UNIFORM_SPACE const DirectionalLight* light = &directional_lights[k];
      const vec3 l = make_vec3(light->to_light[0], light->to_light[1], light->to_light[2]);
      add_light(&block, n, v, l, 1, light->color, shininess, LINK_GATE(frame.point_count + k));
    }
    add_block(&sums, &compensation, &block);
  }
#endif

#ifdef PLANE_KD
  const vec3 kd = LOAD_PLANE3(PLANE_KD);
#else
  const vec3 kd = MATERIAL_FIELD3(MATERIAL_KD);
#endif
  const vec3 diffuse = make_vec3(NONNEGATIVE_TIMES(kd.x, sums.diffuse.x), NONNEGATIVE_TIMES(kd.y, sums.diffuse.y),
                                 NONNEGATIVE_TIMES(kd.z, sums.diffuse.z));
#ifdef SPECULAR
#ifdef PLANE_KS
  const vec3 ks = LOAD_PLANE3(PLANE_KS);
#else
  const vec3 ks = MATERIAL_FIELD3(MATERIAL_KS);
#endif
  const vec3 specular = make_vec3(NONNEGATIVE_TIMES(ks.x, sums.specular.x), NONNEGATIVE_TIMES(ks.y, sums.specular.y),
                                  NONNEGATIVE_TIMES(ks.z, sums.specular.z));
#else
  const vec3 specular = make_vec3(zero, zero, zero);
#endif
#ifdef AMBIENT
#ifdef PLANE_KA
  const vec3 ka = LOAD_PLANE3(PLANE_KA);
#else
  const vec3 ka = MATERIAL_FIELD3(MATERIAL_KA);
#endif
  const vec3 ambient = make_vec3(ka.x * frame.ambient[0], ka.y * frame.ambient[1], ka.z * frame.ambient[2]);
#else
  const vec3 ambient = make_vec3(zero, zero, zero);
#endif

  const floatv shaded_r = unscale(ambient.x + diffuse.x + specular.x, radiance_scale_a, radiance_scale_b);
  const floatv shaded_g = unscale(ambient.y + diffuse.y + specular.y, radiance_scale_a, radiance_scale_b);
  const floatv shaded_b = unscale(ambient.z + diffuse.z + specular.z, radiance_scale_a, radiance_scale_b);
  STORE_OUTPUT(background ? (floatv)frame.background[0] : shaded_r, group, out_rgba);
  STORE_OUTPUT(background ? (floatv)frame.background[1] : shaded_g, group, out_rgba + plane_stride);
  STORE_OUTPUT(background ? (floatv)frame.background[2] : shaded_b, group, out_rgba + 2 * (size_t)plane_stride);
  STORE_OUTPUT(background ? (floatv)0.0f : (floatv)1.0f, group, out_rgba + 3 * (size_t)plane_stride);
#ifdef WRITE_TERMS
  /* Background lanes: the host ignores terms where alpha is 0. */
  store3(ambient, radiance_scale_a, radiance_scale_b, group, out_terms, plane_stride);
  store3(diffuse, radiance_scale_a, radiance_scale_b, group, out_terms + 3 * (size_t)plane_stride, plane_stride);
  store3(specular, radiance_scale_a, radiance_scale_b, group, out_terms + 6 * (size_t)plane_stride, plane_stride);
#endif
}
