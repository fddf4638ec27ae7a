#include "shading/shadow_inputs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "geometry/device_geometry.h"
#include "geometry/scene_bvh.h"
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
  std::vector<float> depth;
  if (mode == ShadowMode::screen) {
    ScreenDepth screen = screen_depth(scene.camera, gbuffer, settings.steps, static_cast<float>(settings.thickness));
    frame.march = screen.march;
    depth = std::move(screen.depth);
    device.nodes = table_buffer(context, std::vector<BvhNode>());
    device.primitives = table_buffer(context, std::vector<ShadowPrimitive>());
    device.planes = table_buffer(context, std::vector<ShadowPlane>());
  } else {
    const SceneBvh bvh = build_scene_bvh(flatten_objects(scene.objects), PHONGCL_BVH_MAX_DEPTH);
    const DeviceGeometry geometry = pack_device_geometry(bvh, eye);
    const ShadowGeometryBuffers buffers = upload_shadow_geometry(context, geometry);
    device.nodes = buffers.nodes;
    device.primitives = buffers.primitives;
    device.planes = buffers.planes;
    frame.node_count = buffers.node_count;
    frame.plane_count = buffers.plane_count;
    device.triangles = bvh.shapes.triangles.size();
    device.spheres = bvh.shapes.spheres.size();
    device.unbounded_planes = geometry.planes.size();
  }
  device.depth = table_buffer(context, depth);
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
  return "geometry: " + lights + ", a BVH of " + std::to_string(device.triangles) + " triangles and " +
         std::to_string(device.spheres) + " spheres, " + std::to_string(device.unbounded_planes) + " planes (built in " +
         built + ")";
}

std::vector<cl_uint> shadow_casters(const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights) {
  std::vector<cl_uint> casters;
  for (const Light& light : lights)
    if (light.type != LightType::directional) casters.push_back(light.shadows ? 1u : 0u);
  for (const Light& light : lights)
    if (light.type == LightType::directional) casters.push_back(light.shadows ? 1u : 0u);
  for (const AreaLight& light : area_lights) casters.push_back(light.shadows ? 1u : 0u);
  return casters;
}

}  // namespace phongcl
