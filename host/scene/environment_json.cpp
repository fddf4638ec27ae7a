#include "scene/environment_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/scene_check.h"

namespace phongcl {

bool is_environment_light(const JsonValue& value) {
  const JsonObject object = value.object();
  return object.has("type") && object.at("type").string() == "environment";
}

EnvironmentLight read_environment_light(const JsonObject& object, const std::filesystem::path& source) {
  object.expect_keys({"type", "color", "file", "rotation", "strength", "rays", "shadows", "group"});
  EnvironmentLight light;
  const auto color = object.find("color");
  const auto file = object.find("file");
  if (color.has_value() == file.has_value())
    object.value().fail("needs one of \"color\" (a uniform world) or \"file\" (an equirect EXR), not both or neither");
  if (color) {
    light.color = color->vec3();
    const std::vector<JsonValue> components = color->elements();
    for (int i = 0; i < 3; ++i)
      if (light.color[i] < 0.0) components[i].fail("must be >= 0 (got " + format_number(light.color[i]) + ")");
  } else {
    const std::filesystem::path path = file->string();
    if (path.empty()) file->fail("must not be empty");
    light.file = path.is_absolute() ? path : source.parent_path() / path;
  }
  if (auto rotation = object.find("rotation")) light.rotation_deg = rotation->number();
  if (auto strength = object.find("strength")) {
    light.strength = strength->number();
    if (!(light.strength >= 0.0 && light.strength <= kMaxEnvironmentStrength))
      strength->fail("must be from 0 to " + format_number(kMaxEnvironmentStrength) + " (got " +
                     format_number(light.strength) + ")");
  }
  if (auto rays = object.find("rays")) {
    light.rays = rays->integer();
    if (light.rays < 1 || light.rays > kMaxEnvironmentRays)
      rays->fail("must be a whole number from 1 to " + std::to_string(kMaxEnvironmentRays) + " (got " +
                 std::to_string(light.rays) + ")");
  }
  if (auto shadows = object.find("shadows")) light.shadows = shadows->boolean();
  if (auto group = object.find("group")) {
    light.group = group->string();
    if (!valid_light_group_name(light.group)) group->fail(kLightGroupNameRule);
  }
  return light;
}

void check_environment_light(const EnvironmentLight& light) {
  auto require = [](bool ok, const char* field, const std::string& problem) {
    if (!ok) throw std::invalid_argument(std::string("environment.") + field + ": " + problem);
  };
  require(finite(light.color) && light.color.x >= 0.0 && light.color.y >= 0.0 && light.color.z >= 0.0, "color",
          "must be finite and >= 0");
  require(std::isfinite(light.rotation_deg), "rotation", "must be finite");
  require(light.strength >= 0.0 && light.strength <= kMaxEnvironmentStrength, "strength",
          "must be from 0 to " + format_number(kMaxEnvironmentStrength));
  require(light.rays >= 0 && light.rays <= kMaxEnvironmentRays, "rays",
          "must be 1 to " + std::to_string(kMaxEnvironmentRays) + " (0: the shade's default)");
  require(light.group.empty() || valid_light_group_name(light.group), "group", kLightGroupNameRule);
}

}  // namespace phongcl
