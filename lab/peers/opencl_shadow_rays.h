#pragma once
// kernels/shadow_rays.cl: the shading kernel's shadow rays and BVH traversal (kernels/shadow.h,
// kernels/bvh.h) on their own, so they can be checked ray by ray against the double reference and
// timed against the Embree peer on the same rays.
#include <vector>

#include <glm/glm.hpp>

#include "cl/program_cache.h"
#include "geometry/device_geometry.h"
#include "peers/shadow_ray_set.h"
#include "scene/scene.h"

namespace phongcl {

class OpenClShadowRays {
 public:
  // lanes: rays per work-item (1, 2, 4, 8, 16); 0 takes the device's preferred float width, as
  // the shading kernel does.
  OpenClShadowRays(const ComputeContext& compute, ProgramCache& cache, const DeviceGeometry& geometry, int lanes = 0);

  // Every light's rays from the frame's shaded pixels (packed relative to `eye`).
  ShadowRaySet make_rays(const PackedFrame& frame, const Scene& scene, const glm::dvec3& eye, float offset_scale);

  // 1 where a ray is blocked, 0 where not (and in empty slots); the trace kernel's time from its
  // profiling event in kernel_ms.
  std::vector<float> trace(const ShadowRaySet& rays, double* kernel_ms = nullptr);

  int lanes() const { return lanes_; }

 private:
  ComputeContext compute_;
  int lanes_;
  cl::Program program_;
  cl::Buffer nodes_, primitives_, planes_;
  cl_uint node_count_, plane_count_;
};

}  // namespace phongcl
