#include "reference/reference_environment.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <numbers>

#include "exr/exr_channels.h"
#include "reference/reference_shadows.h"

namespace phongcl {

using std::numbers::pi;

namespace {

ReferenceMap read_map(const std::filesystem::path& path) {
  ReferenceMap map;
  exr::InputExr file(path);
  map.width = file.data_window().width();
  map.height = file.data_window().height();
  const std::size_t texels = static_cast<std::size_t>(map.width) * map.height;
  std::vector<float> interleaved(3 * texels);
  file.read({{"R", interleaved.data(), 3}, {"G", interleaved.data() + 1, 3}, {"B", interleaved.data() + 2, 3}});
  map.rgb.assign(interleaved.begin(), interleaved.end());
  return map;
}

}  // namespace

const ReferenceMap& reference_map(const EnvironmentLight& light) {
  static std::mutex mutex;
  static std::map<std::string, ReferenceMap> maps;
  const std::lock_guard<std::mutex> lock(mutex);
  if (light.file.empty()) {
    ReferenceMap& uniform = maps[""];
    uniform = {1, 1, {light.color.x, light.color.y, light.color.z}};
    return uniform;
  }
  const auto modified = std::filesystem::last_write_time(light.file).time_since_epoch().count();
  const std::string key = light.file.string() + "@" + std::to_string(modified);
  auto found = maps.find(key);
  if (found == maps.end()) found = maps.emplace(key, read_map(light.file)).first;
  return found->second;
}

glm::dvec3 integrate_environment(const EnvironmentLight& light, const ReferenceMap& map,
                                 const std::function<glm::dvec3(const glm::dvec3&)>& lobe) {
  // The lookup direction: into the world, then the Mapping node's rotation about +Z.
  const double turn = light.rotation_deg * pi / 180.0;
  const glm::dmat3 rotate_z(glm::dvec3(std::cos(turn), std::sin(turn), 0.0), glm::dvec3(-std::sin(turn), std::cos(turn), 0.0),
                            glm::dvec3(0.0, 0.0, 1.0));  // columns
  const glm::dmat3 to_world = glm::transpose(rotate_z * light.to_world);  // a rotation's inverse
  // Cells at most 1/256 of the turn wide and 1/128 of the half turn tall.
  const int split_x = (256 + map.width - 1) / map.width, split_y = (128 + map.height - 1) / map.height;
  const int columns = map.width * split_x, rows = map.height * split_y;
  glm::dvec3 sum(0.0);
  for (int row = 0; row < rows; ++row) {
    const double polar_top = pi * row / rows, polar_bottom = pi * (row + 1) / rows;
    const double polar = 0.5 * (polar_top + polar_bottom);
    const double cell_solid_angle = (2.0 * pi / columns) * (std::cos(polar_top) - std::cos(polar_bottom));
    const int y = row / split_y;
    for (int column = 0; column < columns; ++column) {
      // u = 1/2 - azimuth / 2 pi (Cycles' equirectangular mapping): the middle column looks along +X.
      const double u = (column + 0.5) / columns, azimuth = 2.0 * pi * (0.5 - u);
      const glm::dvec3 w(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
      const glm::dvec3 weight = lobe(to_world * w);
      if (weight == glm::dvec3(0.0)) continue;
      const double* texel = &map.rgb[3 * (static_cast<std::size_t>(y) * map.width + column / split_x)];
      sum += glm::dvec3(texel[0], texel[1], texel[2]) * weight * cell_solid_angle;
    }
  }
  return sum * (light.strength / pi);
}

namespace {

// strength (1/pi) sum L(w) max(0, n.w) dw over the map's texels, over the directions `visible` lets
// through (given in n's frame).
template <class Visible>
glm::dvec3 integrate_map(const EnvironmentLight& light, const ReferenceMap& map, const glm::dvec3& n, Visible visible) {
  const double length = glm::length(n);
  if (!(length > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 unit = n / length;
  return integrate_environment(light, map, [&](const glm::dvec3& w) {
    const double cosine = glm::dot(unit, w);
    return glm::dvec3(cosine > 0.0 && visible(w) ? cosine : 0.0);
  });
}

// Whether direction d leaves the scene from a point of unit normal n: a directional light's shadow
// ray, with the kernel's offsets.
bool sky_is_free(const SceneShapes& shapes, const glm::dvec3& position, const glm::dvec3& n, const glm::dvec3& d,
                 const glm::dvec3& eye, double offset_scale) {
  Light sky;
  sky.type = LightType::directional;
  sky.direction = -d;
  ReferenceShadowRay ray;
  if (!reference_shadow_ray_from(position, n, sky, eye, offset_scale, ray)) return false;
  return reference_shadow_ray(shapes, ray.origin, ray.direction, ray.t_max) == RayOutcome::free;
}

}  // namespace

glm::dvec3 reference_environment_light(const EnvironmentLight& light, const ReferenceMap& map, const glm::dvec3& n) {
  return integrate_map(light, map, n, [](const glm::dvec3&) { return true; });
}

glm::dvec3 reference_environment_visible_light(const EnvironmentLight& light, const ReferenceMap& map,
                                               const SceneShapes& shapes, const SurfacePoint& point, const glm::dvec3& eye,
                                               double offset_scale) {
  const double length = glm::length(point.normal);
  if (!(length > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 n = point.normal / length;
  return integrate_map(light, map, n,
                       [&](const glm::dvec3& d) { return sky_is_free(shapes, point.position, n, d, eye, offset_scale); });
}

}  // namespace phongcl
