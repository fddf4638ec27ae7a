#include "scene/scene_check.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace phongcl {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

namespace {

bool non_negative(const glm::dvec3& v) { return finite(v) && v.x >= 0.0 && v.y >= 0.0 && v.z >= 0.0; }

void require(bool ok, const std::string& entry, const char* problem) {
  if (!ok) throw std::invalid_argument(entry + ": " + problem);
}

}  // namespace

void check_lights(const std::vector<Light>& lights, std::size_t material_count) {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    const std::string entry = "lights[" + std::to_string(i) + "]";
    require(non_negative(light.color), entry + ".color", "must be finite and >= 0");
    if (light.type != LightType::directional) {
      require(finite(light.position), entry + ".position", "must be finite");
      require(std::isfinite(light.range) && light.range >= 0.0, entry + ".range", "must be finite and > 0 (0: no range)");
      require(std::isfinite(light.radius) && light.radius >= 0.0, entry + ".radius", "must be finite and >= 0 (0: a point)");
      require(light.angle_deg == 0.0, entry + ".angle_deg", "is used only by directional lights");
    } else {
      require(light.angle_deg >= 0.0 && light.angle_deg < 180.0, entry + ".angle_deg", "must be in [0, 180) degrees");
      require(light.radius == 0.0, entry + ".radius", "is not used by a directional light");
    }
    require(light.shadow_rays >= 0 && light.shadow_rays <= kMaxShadowRays, entry + ".shadow_rays",
            "must be 0 (the shade's) to 1024");
    if (light.type != LightType::point) {
      require(finite(light.direction), entry + ".direction", "must be finite");
      require(light.direction != glm::dvec3(0.0), entry + ".direction", "must not be zero");
    }
    if (light.type == LightType::spot) {
      require(light.cone_angle_deg > 0.0 && light.cone_angle_deg < 180.0, entry + ".cone_angle_deg", "must be in (0, 180)");
      require(light.penumbra_angle_deg >= 0.0 && light.cone_angle_deg / 2.0 + light.penumbra_angle_deg <= 90.0,
              entry + ".penumbra_angle_deg", "must be >= 0 with cone_angle_deg/2 + penumbra_angle_deg <= 90");
      require(std::isfinite(light.cosine_power) && light.cosine_power >= 0.0, entry + ".cosine_power", "must be finite and >= 0");
    }
    if (!light.group.empty()) require(valid_light_group_name(light.group), entry + ".group", kLightGroupNameRule);
    if (light.materials)
      for (int material : *light.materials)
        if (material < 0 || static_cast<std::size_t>(material) >= material_count)
          throw std::invalid_argument(entry + ".materials: material index " + std::to_string(material) +
                                      " is out of range (the scene has " + std::to_string(material_count) + " materials)");
  }
}

bool valid_light_group_name(const std::string& name) {
  return !name.empty() && name.size() <= kMaxLightGroupNameBytes && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

void check_material_table(const std::vector<Material>& materials) {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const Material& m = materials[i];
    const std::string entry = "materials[" + std::to_string(i) + "]";
    require(non_negative(m.ka), entry + ".ka", "must be finite and >= 0");
    require(non_negative(m.kd), entry + ".kd", "must be finite and >= 0");
    require(non_negative(m.ks), entry + ".ks", "must be finite and >= 0");
    require(std::isfinite(m.shininess) && m.shininess >= 0.0, entry + ".shininess", "must be finite and >= 0");
    if (m.specular_model != SpecularModel::principled) continue;
    auto within = [](double x, double high) { return x >= 0.0 && x <= high; };
    require(non_negative(m.base_color), entry + ".base_color", "must be finite and >= 0");
    require(within(m.metallic, 1.0), entry + ".metallic", "must be in [0, 1]");
    require(within(m.roughness, 1.0), entry + ".roughness", "must be in [0, 1]");
    require(within(m.specular, 12.0), entry + ".specular", "must be in [0, 12]");
    require(within(m.specular_tint, 1.0), entry + ".specular_tint", "must be in [0, 1]");
    require(m.version == 1 || m.version == 2, entry + ".version", "must be 1 (Blender 2.8 to 3.6) or 2 (Blender 4.0 on)");
    require(m.ior >= 1.0 && m.ior <= 1000.0, entry + ".ior", "must be in [1, 1000]");
    require(std::isfinite(m.specular_ior_level) && m.specular_ior_level >= 0.0, entry + ".specular_ior_level",
            "must be finite and >= 0");
    require(non_negative(m.specular_tint_color), entry + ".specular_tint", "must be finite and >= 0 (version 2's colour)");
    require(within(m.diffuse_roughness, 1.0), entry + ".diffuse_roughness", "must be in [0, 1]");
  }
}

}  // namespace phongcl
