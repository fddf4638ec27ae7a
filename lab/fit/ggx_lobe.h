// The lobe the LTC table fits: Cycles 3.x's Principled (v1) GGX specular without its Fresnel,
// pi f n.l = pi D G1(v) G1(l) / (4 n.v), in a frame where n = z. It is the reference's own BSDF
// (reference_principled.h) on a white metal, whose Fresnel is 1, with Smith's masking from the
// reference's table so that a fit can afford millions of calls; and GGX's sampling, for the fit's
// integrals.
#pragma once

#include <glm/vec3.hpp>

#include "reference/reference_principled.h"
#include "scene/scene.h"

namespace phongcl {

class GgxLobe {
 public:
  explicit GgxLobe(double roughness);

  double roughness() const { return material_.roughness; }
  // pi f(v, l) n.l for unit v, l; 0 where either is below the horizon.
  double value(const glm::dvec3& v, const glm::dvec3& l) const;
  // The direction l of the sample (xi1, xi2) in [0, 1)^2: GGX's normal density sampled
  // (tan^2 = alpha^2 xi1 / (1 - xi1)) and v mirrored about it.
  glm::dvec3 sample(const glm::dvec3& v, double xi1, double xi2) const;
  // The density in l of those samples, D(h) n.h / (4 v.h); 0 where v.h <= 0.
  double sample_density(const glm::dvec3& v, const glm::dvec3& l) const;

 private:
  Material material_;
  double alpha_;
  const SmithMaskingTable* masking_;
};

}  // namespace phongcl
