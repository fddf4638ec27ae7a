#pragma once
// Screen-space shadows in double precision, from the specification (docs/shadows.md, kernels/shadow.h's
// comments), sharing nothing with the kernel: the shadow ray of reference_shadows.h sampled across
// the frame's depth plane, with each decision's closeness to its thresholds reported.
#include <vector>

#include <glm/glm.hpp>

#include "gbuffer/gbuffer.h"
#include "reference/reference_shadows.h"
#include "scene/scene.h"

namespace phongcl {

// The camera that made the G-buffer (its display window is the camera's image), the frame's
// depth plane (view depth of each shaded pixel's surface, +Inf elsewhere) and the march's settings.
class ReferenceScreenMarch {
 public:
  // thickness > 0: world units; < 0: that fraction of the surface's depth; 0: twice the ray's
  // depth change per step.
  ReferenceScreenMarch(const Camera& camera, const GBuffer& gbuffer, int steps, double thickness);

  // Blocked when a sample lies behind the surface seen at its pixel by more than 2^-9 of that
  // depth and less than the thickness. Borderline when no sample is blocked beyond doubt but one
  // is within `depth_slack` (relative) of either bound, or within `pixel_slack` pixels of a pixel's
  // edge where the pixels either side decide differently.
  RayOutcome march(const ReferenceShadowRay& ray, double depth_slack = 0.0, double pixel_slack = 0.0) const;

 private:
  glm::dvec2 project(const glm::dvec3& point) const;  // eye-relative to pixel coordinates of the plane
  double depth_at(int column, int row) const;

  glm::dvec3 eye_, forward_, right_, up_;
  double scale_, centre_x_, centre_y_;
  int width_, height_, steps_;
  double thickness_, near_ = 0.0, far_ = 0.0;
  std::vector<double> depth_;
};

}  // namespace phongcl
