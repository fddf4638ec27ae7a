#pragma once
// kernels/shadow_rays.cl: the shading kernel's shadow rays, BVH traversal and tiled shadow culling
// (kernels/shadow.h, bvh.h, shadow_cull.cl) on their own, so they can be checked ray by ray against
// the double reference, timed against the Embree peer on the same rays, and costed per frame.
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "cl/program_cache.h"
#include "geometry/device_geometry.h"
#include "peers/shadow_ray_set.h"
#include "scene/scene.h"
#include "shading/screen_depth.h"
#include "shading/shadow_culling.h"

namespace phongcl {

class OpenClShadowRays {
 public:
  // lanes: rays per work-item (1, 2, 4, 8, 16); 0 takes the device's preferred float width, as
  // the shading kernel does.
  OpenClShadowRays(const ComputeContext& compute, ProgramCache& cache, const DeviceGeometry& geometry, int lanes = 0);

  // The frame (packed relative to `eye`, width x height pixels) and the scene's lights, kept on
  // the device for what follows.
  void set_frame(const PackedFrame& frame, int width, int height, const Scene& scene, const glm::dvec3& eye,
                 float offset_scale);

  // Every light's rays from the frame's shaded pixels.
  ShadowRaySet make_rays();
  // Every light's soft shadow rays, `rays` per pixel (soft_shadow.h): a point light as a sphere of
  // radius `size`, a directional one as a sun whose angular radius has tangent `size`; light after
  // light, ray k after ray k - 1, each a frame of slots.
  ShadowRaySet make_soft_rays(float size, int rays);

  // 1 where a ray is blocked, 0 where not (and in empty slots); every ray traverses the BVH. The
  // trace kernel's time from its profiling event in kernel_ms.
  std::vector<float> trace(const ShadowRaySet& rays, double* kernel_ms = nullptr);

  // Per pixel, how many of the lights' rays are blocked, every light in one work-item as shading
  // meets them: every ray traversing the BVH, with tiled culling (kernels/shadow_cull.cl), or by the
  // screen-space march (`screen` then holds the depth plane and camera).
  enum class Method { traverse = 0, culled = 1, screen = 2 };
  struct Counts {
    std::vector<float> blocked_lights;  // per pixel slot
    double culling_ms = 0.0;  // tile boxes, both culling passes (profiling events) and the host's prefix sum
    double kernel_ms = 0.0;
    double candidates_per_pair = 0.0;  // runs per (tile, light) that has a list
    double traversing_pairs = 0.0;     // fraction of (tile, light) pairs beyond the list's limit
  };
  Counts count_blocked(Method method, int tile_size = 16, const ScreenDepth* screen = nullptr);

  int lanes() const { return lanes_; }

 private:
  // `frames` launches of stride_ rays each, one per frame: `launch(f, buffer)` enqueues frame f's ray
  // kernel writing into `buffer`, whose planes go to the set at f * stride_.
  ShadowRaySet gather_frames(std::size_t frames, const std::function<void(std::size_t, const cl::Buffer&)>& launch);

  ComputeContext compute_;
  int lanes_;
  cl::Program program_;
  ShadowGeometryBuffers geometry_;
  ShadowCuller culler_;
  // The frame of set_frame().
  cl::Buffer pixels_, materials_, lights_;
  std::size_t stride_ = 0, light_count_ = 0;
  int width_ = 0, height_ = 0;
  float offset_scale_ = 0.0f, eye_extent_ = 0.0f;
};

}  // namespace phongcl
