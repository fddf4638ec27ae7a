/* Shadow rays alone, for testing kernels/bvh.h against the double reference and timing it against
 * other ray tracers on the same rays (the lab's Embree peer). Each work-item handles PHONGCL_LANES
 * consecutive pixels or rays as one packet, as the shading kernel's work-items do.
 *   PHONGCL_LANES=n   pixels (rays) per work-item
 * Rays: 7 planes of `stride` floats, eye-relative: origin x y z, direction x y z, t_max; a ray with
 * t_max <= 0 is padding (a background pixel, or one facing away from the light) and is not traced. */
#include "shadow.h"

/* One light's shadow rays from packed pixels (planes of `stride`: position - eye x y z, normal x y z;
 * material index < 0: background), built as the shading kernel builds them (shadow.h). `light` is
 * the light's position - eye, or for a directional light (directional != 0) the unit l. */
__kernel void make_shadow_rays(__global const float* restrict pixels, __global const int* restrict material_index,
                               const uint stride, const float light_x, const float light_y, const float light_z,
                               const int directional, const float offset_scale, const float eye_extent,
                               __global float* restrict rays) {
  const size_t group = get_global_id(0);
  const vec3 p = make_vec3(TO_REALV(VLOAD_FLOAT(group, pixels)), TO_REALV(VLOAD_FLOAT(group, pixels + stride)),
                           TO_REALV(VLOAD_FLOAT(group, pixels + 2 * (size_t)stride)));
  const vec3 n = unit_or_zero(make_vec3(TO_REALV(VLOAD_FLOAT(group, pixels + 3 * (size_t)stride)),
                                        TO_REALV(VLOAD_FLOAT(group, pixels + 4 * (size_t)stride)),
                                        TO_REALV(VLOAD_FLOAT(group, pixels + 5 * (size_t)stride))));
  const intv shaded = VLOAD_INT(group, material_index) >= 0;
  ShadowRay ray;
  realv facing;
  if (directional) {
    const vec3 l = make_vec3((realv)light_x, (realv)light_y, (realv)light_z);
    ray = shadow_ray_to_direction(p, n, l, offset_scale, eye_extent);
    facing = dot3(n, l);
  } else {
    const vec3 toward = make_vec3(light_x - p.x, light_y - p.y, light_z - p.z);
    vec3 scaled = toward; /* distance_in_range() may rescale it, keeping its direction */
    realv distance, inverse_distance;
    distance_in_range(&scaled, &distance, &inverse_distance);
    ray = shadow_ray_to_point(p, n, toward, inverse_distance, offset_scale, eye_extent);
    facing = dot3(n, scaled);
  }
  const intv traced = shaded & LANE_MASK(facing > 0);
  const vec3 o = ray.origin, d = ray.direction;
  const realv t_max = SELECT(LANE_MASK(ray.t_max > 0) & traced, ray.t_max, 0);
  VSTORE_FLOAT(TO_FLOATV(o.x), group, rays);
  VSTORE_FLOAT(TO_FLOATV(o.y), group, rays + stride);
  VSTORE_FLOAT(TO_FLOATV(o.z), group, rays + 2 * (size_t)stride);
  VSTORE_FLOAT(TO_FLOATV(d.x), group, rays + 3 * (size_t)stride);
  VSTORE_FLOAT(TO_FLOATV(d.y), group, rays + 4 * (size_t)stride);
  VSTORE_FLOAT(TO_FLOATV(d.z), group, rays + 5 * (size_t)stride);
  VSTORE_FLOAT(TO_FLOATV(t_max), group, rays + 6 * (size_t)stride);
}

/* Out: 1 where the ray is blocked, else 0. */
__kernel void trace_shadow_rays(__global const float* restrict rays, const uint stride,
                                /* the shadow geometry (bvh_layout.h) */
                                __global const BvhNode* restrict nodes, const uint node_count,
                                __global const ShadowPrimitive* restrict primitives,
                                __global const ShadowPlane* restrict planes, const uint plane_count,
                                __global float* restrict blocked) {
  const size_t group = get_global_id(0);
  const vec3 origin = make_vec3(TO_REALV(VLOAD_FLOAT(group, rays)), TO_REALV(VLOAD_FLOAT(group, rays + stride)),
                                TO_REALV(VLOAD_FLOAT(group, rays + 2 * (size_t)stride)));
  const vec3 direction = make_vec3(TO_REALV(VLOAD_FLOAT(group, rays + 3 * (size_t)stride)),
                                   TO_REALV(VLOAD_FLOAT(group, rays + 4 * (size_t)stride)),
                                   TO_REALV(VLOAD_FLOAT(group, rays + 5 * (size_t)stride)));
  const realv t_max = TO_REALV(VLOAD_FLOAT(group, rays + 6 * (size_t)stride));
  const ShadowRay ray = make_shadow_ray(origin, direction, t_max);
  const intv hit = shadow_ray_blocked(nodes, node_count, primitives, planes, plane_count, &ray, LANE_MASK(t_max > 0));
  VSTORE_FLOAT(TO_FLOATV(hit & 1), group, blocked);
}
