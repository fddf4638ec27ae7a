#pragma once
// A scene file light of type "area": a rect or disk emitter (docs/formats.md "Scene JSON").
#include "scene/json_reader.h"
#include "scene/scene.h"

namespace phongcl {

// The largest size (a rect's width or height, a disk's diameter) of an area light. The kernel forms
// its area and its axes' squared lengths in float (kernels/area_light.h: the record's area, the
// emitter's extent): at most about 3 (1e18)^2 = 3e36, a hundredth of float's largest (3.4e38). A rect
// of 1e20 x 1e20 overflowed them to infinity and shaded to NaN.
inline constexpr double kMaxAreaLightSize = 1e18;

// Reads and validates one area light; fails naming the file and the entry (a size <= 0 or above
// kMaxAreaLightSize, a zero direction, up parallel to direction, an unknown shape, a key another
// light type uses).
AreaLight read_area_light(const JsonObject& object);

// A light's "shadow_rays": a whole number from 1 to kMaxShadowRays, else fails naming the file.
int read_shadow_rays(const JsonValue& value);

// The checks of read_area_light for area lights built in code: std::invalid_argument naming the
// entry ("area_lights[0].size: must be finite and > 0").
void check_area_lights(const std::vector<AreaLight>& lights);

}  // namespace phongcl
