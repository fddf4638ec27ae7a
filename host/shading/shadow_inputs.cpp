#include "shading/shadow_inputs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/device_geometry.h"
#include "geometry/scene_bvh.h"
#include "shading/light_order.h"
#include "shading/screen_depth.h"
#include "shading/shadow_buffers.h"

namespace phongcl {

ShadowDevice make_shadow_device(const cl::Context& context, const Scene& scene, const GBuffer& gbuffer, ShadowMode mode,
                                const ShadowSettings& settings, bool half_storage) {
  const auto start = std::chrono::steady_clock::now();
  const glm::dvec3& eye = scene.camera.eye;
  ShadowDevice device;
  ShadowFrame& frame = device.frame;
  frame.offset_scale = half_storage ? PHONGCL_SHADOW_OFFSET_HALF : PHONGCL_SHADOW_OFFSET_FLOAT;
  frame.eye_extent = static_cast<float>(std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)}));
  if (mode == ShadowMode::screen) {
    ScreenDepth screen = screen_depth(scene.camera, gbuffer, settings.steps, static_cast<float>(settings.thickness));
    frame.march = screen.march;
    device.geometry = upload_shadow_geometry(context, DeviceGeometry{}, screen.depth);
  } else {
    const SceneBvh bvh = build_scene_bvh(flatten_objects(scene.objects), PHONGCL_BVH_MAX_DEPTH);
    const DeviceGeometry geometry = pack_device_geometry(bvh, eye);
    device.geometry = upload_shadow_geometry(context, geometry);
    frame.node_count = device.geometry.node_count;
    frame.plane_count = device.geometry.plane_count;
    device.triangles = bvh.shapes.triangles.size();
    device.spheres = bvh.shapes.spheres.size();
    device.unbounded_planes = geometry.planes.size();
    device.culled = bvh.shapes.bounded_count() <= kShadowCullingMaxShapes;
  }
  device.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return device;
}

std::string describe_shadows(ShadowMode mode, int casters, const ShadowSettings& settings, const ShadowDevice& device) {
  char built[64];
  std::snprintf(built, sizeof built, "%.1f ms", device.build_ms);
  const std::string lights = std::to_string(casters) + (casters == 1 ? " light" : " lights");
  if (mode == ShadowMode::screen)
    return "screen: " + lights + ", " + std::to_string(settings.steps) + " steps, thickness " +
           format_shadow_thickness(settings.thickness) + " (depth plane in " + built + ")";
  const std::string culled = device.culled ? ", culled in " + std::to_string(kShadowCullingTile) + "x" +
                                                 std::to_string(kShadowCullingTile) + " tiles"
                                           : "";
  return "geometry: " + lights + ", a BVH of " + std::to_string(device.triangles) + " triangles and " +
         std::to_string(device.spheres) + " spheres, " + std::to_string(device.unbounded_planes) + " planes (built in " +
         built + ")" + culled;
}

namespace {

ShadowLight shadow_light(const glm::dvec3& where, bool directional, float half_extent) {
  return {{static_cast<float>(where.x), static_cast<float>(where.y), static_cast<float>(where.z)},
          directional ? 1u : 0u,
          {half_extent, half_extent, half_extent},
          0.0f};
}

}  // namespace

ShadowCasters shadow_casters(const Scene& scene, const ShadowSettings& settings) {
  ShadowCasters casters;
  const glm::dvec3& eye = scene.camera.eye;
  // `extent`: how far from `where` a soft light's rays may end (its bounding sphere), 0 when hard.
  auto add = [&](bool casts, const glm::dvec3& where, bool directional, int rays, double size, double extent) {
    casters.words.push_back(casts ? static_cast<cl_uint>(casters.lights.size() + 1) : 0u);
    // Rounded up past float's rounding of the kernel's sample points.
    const float half_extent = rays > 1 ? static_cast<float>(extent * (1.0 + 0x1p-20)) : 0.0f;
    if (casts) casters.lights.push_back(shadow_light(where, directional, half_extent));
    casters.soft.push_back({static_cast<cl_uint>(rays), static_cast<float>(size)});
  };
  for_each_light_in_kernel_order(scene.lights, [&](const Light& light) {
    const int rays = shadow_rays(light, settings);
    if (light.type == LightType::directional) {
      const double half_angle = light.angle_deg / 2.0 * std::numbers::pi / 180.0;
      add(light.shadows, -glm::normalize(light.direction), true, rays, std::tan(half_angle), 0.0);
    } else {
      add(light.shadows, light.position - eye, false, rays, light.radius, light.radius);
    }
  });
  for (const AreaLight& light : scene.area_lights)  // half the diagonal bounds the emitter in any orientation
    add(light.shadows, light.position - eye, false, shadow_rays(light, settings), 0.0,
        0.5 * std::hypot(light.size.x, light.size.y));
  return casters;
}

}  // namespace phongcl
