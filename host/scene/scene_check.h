#pragma once
// Checks for lights and materials built in code (the scene file's reader checks its own), and
// readers for a JSON array of lights or materials in the scene file's form.
#include <filesystem>
#include <limits>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace phongcl {

// Throws std::invalid_argument naming the entry ("lights[2].color: must be finite and >= 0") for
// non-finite values, negative colours or shininess, a zero direction, or a linked material index
// not below `material_count` (the rules the scene file's reader applies, for lights built in code).
void check_lights(const std::vector<Light>& lights, std::size_t material_count);
void check_material_table(const std::vector<Material>& materials);

// Every component finite: no NaN or infinity.
bool finite(const glm::dvec3& v);

// A light group names EXR layers (group.<name>.R): letters, digits, '_' and '-', no separators, and
// at most 63 bytes, Blender's own limit for a light group's name (MAX_NAME, 64 with the NUL), far
// inside the 255 bytes OpenEXR keeps of a channel name.
inline constexpr std::size_t kMaxLightGroupNameBytes = 63;
inline constexpr const char* kLightGroupNameRule =
    "must be a name of letters, digits, '_' and '-', at most 63 bytes (Blender's limit for a light group)";
bool valid_light_group_name(const std::string& name);

// `json_text` is an array like the scene file's "lights" or "materials"; InputError names `source`.
// Linked material indices must be below `material_count` (unlimited: any index >= 0).
std::vector<Light> parse_lights(std::string_view json_text, const std::filesystem::path& source,
                                std::size_t material_count = std::numeric_limits<int>::max());
std::vector<Material> parse_materials(std::string_view json_text, const std::filesystem::path& source);

// The same from documents already in memory (Python's dicts and lists, converted without text, so
// that a NaN reaches the reader as a number and is refused as one). The scene file's checks apply.
Scene read_scene(const nlohmann::json& document, const std::filesystem::path& source);
std::vector<Light> read_lights(const nlohmann::json& document, const std::filesystem::path& source,
                               std::size_t material_count = std::numeric_limits<int>::max());
std::vector<Material> read_materials(const nlohmann::json& document, const std::filesystem::path& source);
// Entries of the scene file's "lights" of type "area"; any other type is refused.
std::vector<AreaLight> read_area_lights(const nlohmann::json& document, const std::filesystem::path& source);

}  // namespace phongcl
