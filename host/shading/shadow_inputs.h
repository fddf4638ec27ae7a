#pragma once
// What the shading kernel's shadow tests read on the device (kernels/shadow.h's ShadowInputs): for
// geometry shadows the scene's BVH and planes, for screen-space shadows the frame's depth plane and
// its camera, and which lights cast shadows. The geometry and the depth plane are built once per
// G-buffer, eye and settings; the casters with the light tables.
#include <cstddef>
#include <string>
#include <vector>

#include "cl/opencl.h"
#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/shadow_settings.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {

struct ShadowDevice {
  cl::Buffer nodes, primitives, planes, depth;  // one zeroed element where the mode reads none
  ShadowFrame frame{};
  double build_ms = 0.0;      // the BVH's build (geometry) or the depth plane's (screen)
  std::size_t triangles = 0, spheres = 0, unbounded_planes = 0;  // geometry: what the BVH and the plane list hold
};

// `mode` is geometry or screen (a recipe's resolved mode); positions stored as half get the larger
// self-intersection offset. Throws InputError (a mesh file, or a G-buffer the scene's camera did not
// render) as flatten_objects and screen_depth do.
ShadowDevice make_shadow_device(const cl::Context& context, const Scene& scene, const GBuffer& gbuffer, ShadowMode mode,
                                const ShadowSettings& settings, bool half_storage);

// One line for a report: the mode, the casters, what the rays test, what building it cost.
std::string describe_shadows(ShadowMode mode, int casters, const ShadowSettings& settings, const ShadowDevice& device);

// One word per light in the kernel's table order (point and spot lights, then directional ones,
// then area lights): 1 where the light casts shadows.
std::vector<cl_uint> shadow_casters(const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights);

}  // namespace phongcl
