#pragma once
// The stability catalogue's oracle: the Phong formula (docs/shading.md "The formula") in long
// double, from exactly the values the G-buffer and scene hold. It is a third, independent
// evaluation: the kernel works in float, the reference in double; this one has 11 more bits than
// the reference, so at q = 1e8 its own error (q times a few 2^-64) stays below 1e-10.
#include <array>
#include <cstddef>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

namespace phongcl {

using ExactColor = std::array<long double, 3>;

// L_o of pixel `index`; the scene's background colour for pixels classify_pixel does not shade.
ExactColor exact_shade_pixel(const Scene& scene, const GBuffer& gbuffer, std::size_t index);

}  // namespace phongcl
