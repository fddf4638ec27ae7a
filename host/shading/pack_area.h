#pragma once
// Area lights into the kernel's table (kernels/layout.h AreaLightRecord).
#include <vector>

#include "scene/scene.h"
#include "shading/device_layout.h"

namespace phongcl {

// The scene's area lights, centres relative to the eye (in double), colours times `scale` (the
// frame's 2^-radiance_exponent). A rect's axes are half its width along u and half its height along
// v = normal x u, where v is `up` made orthogonal to the normal (Gram-Schmidt, in double); a
// disk's are its radius along any such pair.
std::vector<AreaLightRecord> pack_area_lights(const Scene& scene, double scale);

// The largest colour component among the area lights, for the frame's radiance scale.
double brightest_area_light(const Scene& scene);

}  // namespace phongcl
