#pragma once
// The Embree peer (Embree 3, Debian's libembree-dev): the same shadow rays as the OpenCL traversal
// (peers/shadow_ray_set.h), against the same float triangles, traced by the best-engineered CPU ray
// tracer there is, on every core. A lab peer only: the product never links Embree.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/scene_shapes.h"
#include "peers/shadow_ray_set.h"

namespace phongcl {

enum class EmbreeApi {
  packet16,  // rtcOccluded16 on the 16 neighbouring pixels a kernel work-item traces (coherent flag)
  single,    // rtcOccluded1 ray by ray
};

const char* to_string(EmbreeApi api);

class EmbreeShadowPeer {
 public:
  // Triangles only, relative to `eye` and rounded to float as the kernel's are (geometry/
  // device_geometry.h); throws std::invalid_argument for a scene with spheres or planes. Built at
  // RTC_BUILD_QUALITY_HIGH, Embree's best BVH for tracing.
  EmbreeShadowPeer(const SceneShapes& shapes, const glm::dvec3& eye);
  ~EmbreeShadowPeer();
  EmbreeShadowPeer(const EmbreeShadowPeer&) = delete;
  EmbreeShadowPeer& operator=(const EmbreeShadowPeer&) = delete;

  // 1 where a ray is blocked, 0 where not (and in empty slots); the wall clock of the parallel
  // loop over the rays in `milliseconds`.
  std::vector<float> trace(const ShadowRaySet& rays, EmbreeApi api, double* milliseconds = nullptr) const;

  double build_milliseconds() const { return build_ms_; }
  // "AVX-512 (16-wide packets native), 2 threads" and the like.
  std::string describe() const;

 private:
  struct Handles;
  Handles* handles_;
  double build_ms_ = 0.0;
};

}  // namespace phongcl
