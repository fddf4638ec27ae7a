/* Shadow rays alone, for testing kernels/bvh.h against the double reference and timing it against
 * other ray tracers on the same rays (the lab's Embree peer). Each work-item handles PHONGCL_LANES
 * consecutive pixels or rays as one packet, as the shading kernel's work-items do.
 *   PHONGCL_LANES=n   pixels (rays) per work-item
 * Rays: 7 planes of `stride` floats, eye-relative: origin x y z, direction x y z, t_max; a ray with
 * t_max <= 0 is padding (a background pixel, or one facing away from the light) and is not traced. */
#include "emitter.h"
#include "sampling.h"
#include "shadow.h"
#include "tiles.h"

/* A pixel's shadow ray toward one light (shadow.h), and in `traced` the lanes that need one: shaded
 * and facing the light. */
static inline ShadowRay light_ray(vec3 p, vec3 n, ShadowLight light, float offset_scale, float eye_extent, intv* traced) {
  const vec3 where = make_vec3((realv)light.where[0], (realv)light.where[1], (realv)light.where[2]);
  return shadow_ray_toward(p, n, where, light.directional, offset_scale, eye_extent, traced);
}

/* Packed pixels: planes of `stride` (position - eye x y z, normal x y z; material index < 0:
 * background). */
static inline vec3 pixel_position(__global const float* pixels, uint stride, size_t group) {
  return make_vec3(TO_REALV(VLOAD(group, pixels)), TO_REALV(VLOAD(group, pixels + stride)),
                   TO_REALV(VLOAD(group, pixels + 2 * (size_t)stride)));
}
static inline vec3 pixel_normal(__global const float* pixels, uint stride, size_t group) {
  return unit_or_zero(make_vec3(TO_REALV(VLOAD(group, pixels + 3 * (size_t)stride)),
                                TO_REALV(VLOAD(group, pixels + 4 * (size_t)stride)),
                                TO_REALV(VLOAD(group, pixels + 5 * (size_t)stride))));
}

/* A packet of rays into the 7 planes of `rays`; t_max 0 in the lanes not `traced`. */
static inline void store_ray(const ShadowRay* ray, intv traced, size_t group, uint stride, __global float* rays) {
  const vec3 o = ray->origin, d = ray->direction;
  const realv t_max = SELECT(LANE_MASK(ray->t_max > 0) & traced, ray->t_max, 0);
  VSTORE(TO_FLOATV(o.x), group, rays);
  VSTORE(TO_FLOATV(o.y), group, rays + stride);
  VSTORE(TO_FLOATV(o.z), group, rays + 2 * (size_t)stride);
  VSTORE(TO_FLOATV(d.x), group, rays + 3 * (size_t)stride);
  VSTORE(TO_FLOATV(d.y), group, rays + 4 * (size_t)stride);
  VSTORE(TO_FLOATV(d.z), group, rays + 5 * (size_t)stride);
  VSTORE(TO_FLOATV(t_max), group, rays + 6 * (size_t)stride);
}

/* One light's shadow rays from packed pixels, as the shading kernel builds them. */
__kernel void make_shadow_rays(__global const float* restrict pixels, __global const int* restrict material_index,
                               const uint stride, __global const ShadowLight* restrict lights, const uint light,
                               const float offset_scale, const float eye_extent, __global float* restrict rays) {
  const size_t group = get_global_id(0);
  intv traced = VLOAD(group, material_index) >= 0;
  const ShadowRay ray = light_ray(pixel_position(pixels, stride, group), pixel_normal(pixels, stride, group), lights[light],
                                  offset_scale, eye_extent, &traced);
  store_ray(&ray, traced, group, stride, rays);
}

/* Ray `k` of a light's soft shadow from packed pixels, as the shading kernel makes them
 * (soft_shadow.h): a point light as a sphere of radius `size`, a directional one as a sun whose
 * angular radius has tangent `size`; toward point k of the pixel's shifted lattice on the emitter
 * (the pixel's number its slot here, the stream the light's). A point the diffuse integrand weighs 0
 * (below the pixel's horizon) is not traced, as in the kernel. */
__kernel void make_soft_shadow_rays(__global const float* restrict pixels, __global const int* restrict material_index,
                                    const uint stride, __global const ShadowLight* restrict lights, const uint light,
                                    const float size, const uint k, const float offset_scale, const float eye_extent,
                                    __global float* restrict rays) {
  const size_t group = get_global_id(0);
  const vec3 p = pixel_position(pixels, stride, group), n = pixel_normal(pixels, stride, group);
  const ShadowLight source = lights[light];
  const vec3 center = make_vec3((realv)source.where[0], (realv)source.where[1], (realv)source.where[2]);
  const int directional = source.directional != 0;
  const Emitter emitter = directional ? sun_emitter(center, size) : sphere_emitter(center, size, p);
  realv s, t;
  lattice_point(k, lattice_shift((uint)(group * PHONGCL_LANES), light), &s, &t);
  const vec3 offset = emitter_offset(&emitter, s, t);
  const vec3 d = add3(directional ? center : sub3(center, p), offset);
  const vec3 where = directional ? unit_or_zero(d) : add3(center, offset);
  intv traced = (VLOAD(group, material_index) >= 0) & LANE_MASK(emitter_weight(d, n, emitter.normal) > 0);
  const ShadowRay ray = shadow_ray_toward(p, n, where, directional, offset_scale, eye_extent, &traced);
  store_ray(&ray, traced, group, stride, rays);
}

static inline ShadowRay load_ray(__global const float* rays, uint stride, size_t group) {
  const vec3 origin = make_vec3(TO_REALV(VLOAD(group, rays)), TO_REALV(VLOAD(group, rays + stride)),
                                TO_REALV(VLOAD(group, rays + 2 * (size_t)stride)));
  const vec3 direction = make_vec3(TO_REALV(VLOAD(group, rays + 3 * (size_t)stride)),
                                   TO_REALV(VLOAD(group, rays + 4 * (size_t)stride)),
                                   TO_REALV(VLOAD(group, rays + 5 * (size_t)stride)));
  return make_shadow_ray(origin, direction, TO_REALV(VLOAD(group, rays + 6 * (size_t)stride)));
}

/* Out: 1 where the ray is blocked, else 0. Every ray traverses the BVH. */
__kernel void trace_shadow_rays(__global const float* restrict rays, const uint stride,
                                /* the shadow geometry (shadow_layout.h) */
                                __global const BvhNode* restrict nodes, const uint node_count,
                                __global const ShadowPrimitive* restrict primitives,
                                __global const ShadowPlane* restrict planes, const uint plane_count,
                                __global float* restrict blocked) {
  const size_t group = get_global_id(0);
  const ShadowRay ray = load_ray(rays, stride, group);
  const intv hit = shadow_ray_blocked(nodes, node_count, primitives, planes, plane_count, &ray, LANE_MASK(ray.t_max > 0));
  VSTORE(TO_FLOATV(hit & 1), group, blocked);
}

/* Every light's shadows at once, as the shading kernel meets them: per pixel the number of lights
 * whose ray is blocked, the rays built in registers. Method 0: every ray traverses the BVH; 1: a ray
 * tests its tile's candidates for its light (shadow_cull.cl: pair = light * tile_count + tile), or
 * traverses where the tile has too many; 2: the screen-space march over the depth plane. */
__kernel void count_blocked_lights(__global const float* restrict pixels, __global const int* restrict material_index,
                                   const uint stride, __global const ShadowLight* restrict lights, const uint light_count,
                                   const float offset_scale, const float eye_extent, const int method,
                                   /* tiled culling's lists */
                                   const TileGrid grid, const uint tile_count, __global const uint* restrict counts,
                                   __global const uint* restrict offsets,
                                   __global const ShadowCandidate* restrict candidates,
                                   /* the shadow geometry (shadow_layout.h) */
                                   __global const BvhNode* restrict nodes, const uint node_count,
                                   __global const ShadowPrimitive* restrict primitives,
                                   __global const ShadowPlane* restrict planes, const uint plane_count,
                                   /* the screen-space march's depth plane, in the frame's pixel order */
                                   __global const float* restrict depth, const ScreenMarch march,
                                   __global float* restrict blocked_lights) {
  const size_t group = get_global_id(0);
  const uint tile = tile_of_pixel(grid, (uint)(group * PHONGCL_LANES));
  const intv shaded = VLOAD(group, material_index) >= 0;
  const vec3 p = pixel_position(pixels, stride, group), n = pixel_normal(pixels, stride, group);
  realv blocked_count = 0;
  for (uint k = 0; k < light_count && tile < tile_count; ++k) {
    intv pending = shaded;
    const ShadowRay ray = light_ray(p, n, lights[k], offset_scale, eye_extent, &pending);
    pending &= LANE_MASK(ray.t_max > 0);
    const uint pair = k * tile_count + tile;
    intv hit;
    if (method == 2) hit = screen_march_blocked(depth, march, &ray, pending);
    else if (method == 1 && counts[pair] != PHONGCL_SHADOW_TRAVERSE)
      hit = candidates_block(&candidates[offsets[pair]], counts[pair], primitives, planes, &ray, pending);
    else hit = shadow_ray_blocked(nodes, node_count, primitives, planes, plane_count, &ray, pending);
    blocked_count += TO_REALV(hit & 1);
  }
  VSTORE(TO_FLOATV(blocked_count), group, blocked_lights);
}
