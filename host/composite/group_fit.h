#pragma once
// How phongcl's shading of a light group relates to the renderer's pass of it, with the lights as
// rendered: per channel, one gain for phongcl's diffuse light and one for its specular light, by least
// squares over the pixels phongcl lights, and what is left. The two terms are fitted apart because the
// renderer's BSDF departs from phongcl's differently in each: its glossy lobe (GGX, Fresnel) is not
// phongcl's, its diffuse nearly is. A changed group's composite adds the gains times the change in
// phongcl's terms (composite/composite.h), so what the model leaves out (bounces, the BSDF's
// difference) stays as rendered, and a small move changes the image by a small amount.
#include <glm/vec3.hpp>

#include "../image/image.h"

namespace phongcl {

// phongcl's light of one group, apart: its diffuse and specular terms (RGB of two images of one size).
struct GroupTerms {
  Image diffuse, specular;
};

struct GroupFit {
  glm::dvec3 diffuse_gain{1.0}, specular_gain{1.0};
  double residual = 0.0;   // RMS of the pass minus the fitted terms over RMS of the pass, on the pixels fitted
  std::size_t pixels = 0;  // where phongcl's shading is above zero in some channel
};

// `rendered`: the group's pass; `terms`: phongcl's terms of the same lights. A channel whose specular
// (or diffuse) term is nothing, or no independent of the other, gets one gain for their sum. Gains
// are never negative (the least-squares solution under that bound).
// std::invalid_argument when the sizes differ.
GroupFit fit_group(const Image& rendered, const GroupTerms& terms);

}  // namespace phongcl
