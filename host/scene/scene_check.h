#pragma once
// Checks for lights and materials built in code (the scene file's reader checks its own), and
// readers for a JSON array of lights or materials in the scene file's form.
#include <filesystem>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace phongcl {

// Throws std::invalid_argument naming the entry ("lights[2].color: must be finite and >= 0") for
// non-finite values, negative colours or shininess, or a zero direction.
void check_lights(const std::vector<Light>& lights);
void check_material_table(const std::vector<Material>& materials);

// `json_text` is an array like the scene file's "lights" or "materials"; InputError names `source`.
std::vector<Light> parse_lights(std::string_view json_text, const std::filesystem::path& source);
std::vector<Material> parse_materials(std::string_view json_text, const std::filesystem::path& source);

}  // namespace phongcl
