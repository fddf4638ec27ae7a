#pragma once
// A scene file light of type "environment": the world's uniform colour or equirect EXR
// (docs/formats.md "Scene JSON").
#include <filesystem>

#include "scene/json_reader.h"
#include "scene/scene.h"

namespace phongcl {

// The largest "strength": with the brightest float texel it must stay finite in the kernel's sums.
inline constexpr double kMaxEnvironmentStrength = 1e6;

bool is_environment_light(const JsonValue& value);

// Reads and validates one environment light, "file" resolved relative to `source`'s folder; fails
// naming the file and the entry (both or neither of "color" and "file", a negative colour, a
// strength outside [0, kMaxEnvironmentStrength], a key another light type uses).
EnvironmentLight read_environment_light(const JsonObject& object, const std::filesystem::path& source);

// The checks of read_environment_light for one built in code: std::invalid_argument naming the
// field ("environment.strength: must be finite and >= 0").
void check_environment_light(const EnvironmentLight& light);

}  // namespace phongcl
