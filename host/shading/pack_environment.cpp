#include "shading/pack_environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shading/store3.h"

namespace phongcl {

std::shared_ptr<const IrradianceMap> environment_irradiance(const Scene& scene) {
  if (!scene.environment) return std::make_shared<const IrradianceMap>();
  if (scene.environment->file.empty())
    return std::make_shared<const IrradianceMap>(uniform_irradiance(scene.environment->color));
  return irradiance_of_file(scene.environment->file);
}

double brightest_environment(const Scene& scene, const IrradianceMap& irradiance) {
  if (!scene.environment) return 0.0;
  // A blocked visibility ray subtracts a sky texel: as bright as E / pi at most where the sky is
  // uniform, brighter where it is not.
  double brightest = irradiance.rgb.empty() ? 0.0 : *std::max_element(irradiance.rgb.begin(), irradiance.rgb.end());
  if (!irradiance.sky.rgb.empty())
    brightest = std::max<double>(brightest, *std::max_element(irradiance.sky.rgb.begin(), irradiance.sky.rgb.end()));
  for (const EnvironmentSunCell& sun : irradiance.suns) brightest += std::max({sun.color.x, sun.color.y, sun.color.z});
  return brightest * scene.environment->strength;
}

PackedEnvironment pack_environment(const Scene& scene, const IrradianceMap& irradiance, int rays, double scale) {
  PackedEnvironment packed;
  if (!scene.environment) return packed;
  const EnvironmentLight& light = *scene.environment;
  // The Mapping node turns the lookup direction by +rotation about Z: the map's frame is
  // rotate_z(rotation) * to_world.
  const double angle = light.rotation_deg * std::numbers::pi / 180.0;
  const glm::dmat3 rotate_z(glm::dvec3(std::cos(angle), std::sin(angle), 0.0), glm::dvec3(-std::sin(angle), std::cos(angle), 0.0),
                            glm::dvec3(0.0, 0.0, 1.0));  // columns
  const glm::dmat3 to_map = rotate_z * light.to_world;
  EnvironmentRecord record{};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column) record.to_map[4 * row + column] = static_cast<float>(to_map[column][row]);
  record.scale = static_cast<float>(scale * light.strength);
  record.width = irradiance.width;
  record.height = irradiance.height;
  record.rays = static_cast<layout_uint>(rays);
  record.sun_count = static_cast<layout_int>(irradiance.suns.size());
  record.sky_width = irradiance.sky.width;
  record.sky_height = irradiance.sky.height;
  record.sky_offset = static_cast<layout_uint>(irradiance.rgb.size());
  packed.record.push_back(record);
  packed.texels.assign(irradiance.rgb.begin(), irradiance.rgb.end());
  packed.texels.insert(packed.texels.end(), irradiance.sky.rgb.begin(), irradiance.sky.rgb.end());
  for (const EnvironmentSunCell& sun : irradiance.suns) {
    EnvironmentSun packed_sun{};
    store3(packed_sun.direction, glm::transpose(to_map) * sun.direction);  // to_map is a rotation
    store3(packed_sun.color, sun.color);
    packed.suns.push_back(packed_sun);
  }
  return packed;
}

}  // namespace phongcl
