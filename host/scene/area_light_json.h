#pragma once
// A scene file light of type "area": a rect or disk emitter (docs/formats.md "Scene JSON").
#include "scene/json_reader.h"
#include "scene/scene.h"

namespace phongcl {

// Reads and validates one area light; fails naming the file and the entry (size <= 0, a zero
// direction, up parallel to direction, an unknown shape, a key another light type uses).
AreaLight read_area_light(const JsonObject& object);

// The checks of read_area_light for area lights built in code: std::invalid_argument naming the
// entry ("area_lights[0].size: must be finite and > 0").
void check_area_lights(const std::vector<AreaLight>& lights);

}  // namespace phongcl
