#include "scene/area_light_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/scene_check.h"

namespace phongcl {

namespace {

// up and direction span the rect's plane; below this sine the width axis is noise.
constexpr double kMinimumUpSine = 1e-6;

double up_sine(const AreaLight& light) {
  const double lengths = glm::length(light.up) * glm::length(light.direction);
  return lengths > 0.0 ? glm::length(glm::cross(light.up, light.direction)) / lengths : 0.0;
}

AreaShape read_shape(const JsonValue& value) {
  try {
    return parse_area_shape(value.string());
  } catch (const std::invalid_argument& unknown) {
    value.fail(unknown.what());
  }
}

double read_size(const JsonValue& value) {
  const double size = value.number();
  if (!(size > 0.0 && std::isfinite(size))) value.fail("must be finite and > 0 (got " + format_number(size) + ")");
  if (size > kMaxAreaLightSize)
    value.fail("must be at most " + format_number(kMaxAreaLightSize) + " (got " + format_number(size) + ")");
  return size;
}

}  // namespace

const char* to_string(AreaShape shape) { return shape == AreaShape::rect ? "rect" : "disk"; }

AreaShape parse_area_shape(const std::string& name) {
  for (AreaShape shape : {AreaShape::rect, AreaShape::disk})
    if (name == to_string(shape)) return shape;
  throw std::invalid_argument("'" + name + "' is not an area light shape (expected rect or disk)");
}

int read_shadow_rays(const JsonValue& value) {
  const int rays = value.integer();
  if (rays < 1 || rays > kMaxShadowRays)
    value.fail("must be a whole number from 1 to " + std::to_string(kMaxShadowRays) + " (got " + std::to_string(rays) + ")");
  return rays;
}

AreaLight read_area_light(const JsonObject& object) {
  object.expect_keys({"type", "shape", "position", "direction", "up", "size", "color", "range", "shadows", "shadow_rays", "group"});
  AreaLight light;
  light.shape = read_shape(object.at("shape"));
  light.position = object.at("position").vec3();
  const JsonValue direction = object.at("direction");
  light.direction = direction.vec3();
  if (light.direction == glm::dvec3(0.0)) direction.fail("must not be zero");
  const JsonValue size = object.at("size");
  if (light.shape == AreaShape::rect) {
    const std::vector<JsonValue> sides = size.elements();
    if (sides.size() != 2) size.fail("must be [width, height] for a rect");
    light.size = {read_size(sides[0]), read_size(sides[1])};
    if (auto up = object.find("up")) {
      light.up = up->vec3();
      if (!(up_sine(light) > kMinimumUpSine)) up->fail("must not be zero or parallel to direction");
    } else if (!(up_sine(light) > kMinimumUpSine)) {
      direction.fail("is parallel to the default up (0, 1, 0): give 'up'");
    }
  } else {
    light.size = glm::dvec2(read_size(size));
    if (object.has("up")) object.at("up").fail("is used only by rect area lights (a disk has no orientation)");
  }
  if (auto color = object.find("color")) {
    light.color = color->vec3();
    const std::vector<JsonValue> components = color->elements();
    for (int i = 0; i < 3; ++i)
      if (light.color[i] < 0.0) components[i].fail("must be >= 0 (got " + format_number(light.color[i]) + ")");
  }
  if (auto range = object.find("range")) {
    light.range = range->number();
    if (!(light.range > 0.0)) range->fail("must be > 0 (got " + format_number(light.range) + ")");
  }
  if (auto shadows = object.find("shadows")) light.shadows = shadows->boolean();
  if (auto rays = object.find("shadow_rays")) light.shadow_rays = read_shadow_rays(*rays);
  if (auto group = object.find("group")) {
    light.group = group->string();
    if (!valid_light_group_name(light.group)) group->fail(kLightGroupNameRule);
  }
  return light;
}

void check_area_lights(const std::vector<AreaLight>& lights) {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const AreaLight& light = lights[i];
    const std::string entry = "area_lights[" + std::to_string(i) + "]";
    auto require = [&](bool ok, const char* field, const std::string& problem) {
      if (!ok) throw std::invalid_argument(entry + "." + field + ": " + problem);
    };
    require(finite(light.color) && light.color.x >= 0.0 && light.color.y >= 0.0 && light.color.z >= 0.0, "color",
            "must be finite and >= 0");
    require(finite(light.position), "position", "must be finite");
    require(finite(light.direction) && light.direction != glm::dvec3(0.0), "direction", "must be finite and not zero");
    require(std::isfinite(light.size.x) && std::isfinite(light.size.y) && light.size.x > 0.0 && light.size.y > 0.0,
            "size", "must be finite and > 0");
    require(light.size.x <= kMaxAreaLightSize && light.size.y <= kMaxAreaLightSize, "size",
            "must be at most " + format_number(kMaxAreaLightSize));
    if (light.shape == AreaShape::rect)
      require(finite(light.up) && up_sine(light) > kMinimumUpSine, "up", "must not be zero or parallel to direction");
    require(std::isfinite(light.range) && light.range >= 0.0, "range", "must be finite and > 0 (0: no range)");
    require(light.shadow_rays >= 0 && light.shadow_rays <= kMaxShadowRays, "shadow_rays",
            "must be 1 to " + std::to_string(kMaxShadowRays) + " (0: the shade's default)");
    require(light.group.empty() || valid_light_group_name(light.group), "group", kLightGroupNameRule);
  }
}

}  // namespace phongcl
