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
#include "shading/shadow_buffers.h"
#include "shading/shadow_settings.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {

// Geometry shadows are culled per screen tile (kernels/shadow_cull.cl) where the scene has at most
// this many bounded shapes: on scenes of small shapes each tile's rays then test a few candidates
// (scenes/large: 0.51x the traversal's time, culling included), while on a dense mesh a quarter of
// the tiles outgrow their lists and traverse after paying for the culling (128k triangles: 1.17x).
constexpr std::size_t kShadowCullingMaxShapes = 4096;
// The culling's tiles: 32 x 32 pixels cost least of 8, 16 and 32 on every bundled scene.
constexpr int kShadowCullingTile = 32;

struct ShadowDevice {
  ShadowGeometryBuffers geometry;  // with the depth plane; one zeroed element per table the mode reads none of
  ShadowFrame frame{};
  double build_ms = 0.0;      // the BVH's build (geometry) or the depth plane's (screen)
  std::size_t triangles = 0, spheres = 0, unbounded_planes = 0;  // geometry: what the BVH and the plane list hold
  bool culled = false;        // geometry: tiled shadow culling before each launch
};

// `mode` is geometry or screen (a recipe's resolved mode); positions stored as half get the larger
// self-intersection offset. Throws InputError (a mesh file, or a G-buffer the scene's camera did not
// render) as flatten_objects and screen_depth do.
ShadowDevice make_shadow_device(const cl::Context& context, const Scene& scene, const GBuffer& gbuffer, ShadowMode mode,
                                const ShadowSettings& settings, bool half_storage);

// One line for a report: the mode, the casters, what the rays test, what building it cost.
std::string describe_shadows(ShadowMode mode, int casters, const ShadowSettings& settings, const ShadowDevice& device);

// The lights that cast shadows: one word per light in the kernel's table order (point and spot
// lights, then directional ones, then area lights), 1 + the light's place in `lights` where it casts
// shadows, else 0; and for tiled shadow culling each caster as its rays end, relative to the eye in
// double as the light tables are (an area light's rays run to its centre; with several rays a
// light's run anywhere in its bounding box); and each light's SoftLight, in the same order.
struct ShadowCasters {
  std::vector<cl_uint> words;
  std::vector<ShadowLight> lights;
  std::vector<SoftLight> soft;
};
ShadowCasters shadow_casters(const Scene& scene, const ShadowSettings& settings);

}  // namespace phongcl
