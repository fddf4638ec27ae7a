#pragma once
// How the kernel numbers a scene's lights in its per-light tables (link masks, light groups, shadow
// casters): point and spot lights, then directional lights, each kind in the scene's order (as the
// light records are stored, kernels/layout.h); a table that holds area lights lists them after.
#include <vector>

#include "scene/scene.h"

namespace phongcl {

template <class Visit>
void for_each_light_in_kernel_order(const std::vector<Light>& lights, Visit&& visit) {
  for (const Light& light : lights)
    if (light.type != LightType::directional) visit(light);
  for (const Light& light : lights)
    if (light.type == LightType::directional) visit(light);
}

}  // namespace phongcl
