#pragma once
// The scene's "objects" array: geometry for the G-buffer generator, transforms nesting children.
#include <cstddef>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene.h"

namespace phongcl {

// Material indices are checked against `material_count`, at any depth.
std::vector<Object> read_objects(const JsonValue& array, std::size_t material_count);

}  // namespace phongcl
