#include "shading/pack_area.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shading/store3.h"

namespace phongcl {

using std::numbers::pi;

namespace {

// Any unit vector orthogonal to `normal`: a disk's orientation does not matter.
glm::dvec3 any_orthogonal(const glm::dvec3& normal) {
  const glm::dvec3 away = std::abs(normal.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(away, normal));
}

}  // namespace

double brightest_area_light(const Scene& scene) {
  double brightest = 0.0;
  for (const AreaLight& light : scene.area_lights)
    brightest = std::max({brightest, light.color.x, light.color.y, light.color.z});
  return brightest;
}

std::vector<AreaLightRecord> pack_area_lights(const Scene& scene, double scale) {
  std::vector<AreaLightRecord> records;
  for (const AreaLight& light : scene.area_lights) {
    AreaLightRecord record{};
    const glm::dvec3 normal = glm::normalize(light.direction);
    // v along up made orthogonal to the normal; u = v x normal, so that u x v = normal.
    const glm::dvec3 v = light.shape == AreaShape::rect ? glm::normalize(light.up - glm::dot(light.up, normal) * normal)
                                                        : any_orthogonal(normal);
    const glm::dvec3 u = glm::cross(v, normal);
    store3(record.center, light.position - scene.camera.eye);
    store3(record.normal, normal);
    store3(record.axis_u, u * (light.size.x / 2.0));
    store3(record.axis_v, v * ((light.shape == AreaShape::rect ? light.size.y : light.size.x) / 2.0));  // a disk's diameter is size.x
    store3(record.color, light.color * scale);
    record.shape = light.shape == AreaShape::rect ? AREA_RECT : AREA_DISK;
    record.inverse_range = light.has_range() ? static_cast<float>(1.0 / light.range) : 0.0f;
    const double area = light.shape == AreaShape::rect ? light.size.x * light.size.y : pi / 4.0 * light.size.x * light.size.x;
    record.area = static_cast<float>(area);
    records.push_back(record);
  }
  return records;
}

}  // namespace phongcl
