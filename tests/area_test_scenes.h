#pragma once
// Area-light test scenes: emitters over a floor of tilted surface points, and the error of the
// kernel's image against the reference's where the light is (test_area_lights, test_area_ltc).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "shading_support.h"

namespace phongcl::testing {

inline AreaLight rect_light(glm::dvec3 position, glm::dvec3 direction, glm::dvec3 up, glm::dvec2 size) {
  AreaLight light;
  light.position = position;
  light.direction = direction;
  light.up = up;
  light.size = size;
  return light;
}

inline AreaLight disk_light(glm::dvec3 position, glm::dvec3 direction, double diameter) {
  AreaLight light;
  light.shape = AreaShape::disk;
  light.position = position;
  light.direction = direction;
  light.size = glm::dvec2(diameter);
  return light;
}

struct AreaScene {
  Scene scene;
  GBuffer gbuffer;
};

// Points on and around a floor under the emitters, normals tilted up to 80 degrees: many see an
// emitter cut by their horizon, some are behind one.
inline AreaScene area_scene(const std::vector<AreaLight>& lights, glm::dvec3 ks, double shininess, unsigned seed) {
  RandomSceneSpec spec;
  spec.point_lights = spec.directional_lights = 0;
  spec.materials = 1;
  spec.background_fraction = 0.0;
  auto [scene, gbuffer] = random_scene(spec, seed);
  scene.ambient = glm::dvec3(0.0);
  scene.materials = {{"area", glm::dvec3(0.0), glm::dvec3(1.0), ks, shininess}};
  scene.area_lights = lights;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Drawn one statement at a time: the order of a constructor's arguments is unspecified, and the
  // sanitizer build evaluated them in another order than the release build, shading another scene.
  const auto draw = [&](double scale) { return unit(rng) * scale; };
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    glm::dvec3 p, tilt;
    p.x = draw(2.5), p.y = draw(0.5), p.z = draw(2.5);
    tilt.x = draw(2.5), tilt.y = 1.0, tilt.z = draw(2.5);
    const glm::dvec3 normal = glm::normalize(tilt);
    for (int c = 0; c < 3; ++c) {
      gbuffer.position[c][i] = static_cast<float>(p[c]);
      gbuffer.normal[c][i] = static_cast<float>(normal[c]);
    }
    gbuffer.material[i] = 0.0f;
  }
  return {std::move(scene), std::move(gbuffer)};
}

struct TermError {
  double max_rel = 0.0, median_rel = 0.0;
  std::size_t lit = 0;
  std::size_t worst = 0;  // pixel
  double worst_kernel = 0.0, worst_reference = 0.0;
};

// Error of channel 0 relative to max(reference, 1e-3 of its largest value), where the reference
// exceeds 1e-4 of that: the light's geometry reaches the kernel rounded to float (as a point light's
// position does), which moves E by ~1e-8 of the light's scale, a large share of a faint sliver.
inline TermError term_error(const Image& kernel, const Image& reference) {
  double largest = 0.0;
  for (std::size_t i = 0; i < reference.pixel_count(); ++i) largest = std::max(largest, double(reference.pixel(i)[0]));
  std::vector<double> errors;
  TermError error;
  for (std::size_t i = 0; i < reference.pixel_count(); ++i) {
    const double want = reference.pixel(i)[0];
    if (!(want > 1e-4 * largest)) continue;
    errors.push_back(std::abs(kernel.pixel(i)[0] - want) / std::max(want, 1e-3 * largest));
    if (errors.back() >= error.max_rel) {
      error.max_rel = errors.back();
      error.worst = i;
      error.worst_kernel = kernel.pixel(i)[0];
      error.worst_reference = want;
    }
  }
  error.lit = errors.size();
  if (errors.empty()) return error;
  std::sort(errors.begin(), errors.end());
  error.max_rel = errors.back();
  error.median_rel = errors[errors.size() / 2];
  return error;
}

inline std::vector<AreaLight> emitters(bool rect) {
  std::vector<AreaLight> lights;
  if (rect) {
    lights.push_back(rect_light({0.3, 1.0, -0.2}, {0.1, -1, 0.2}, {0, 0, 1}, {1.6, 0.8}));
    lights.push_back(rect_light({-1.5, 0.3, 1.0}, {1, -0.3, 0}, {0, 1, 0}, {0.9, 1.3}));  // a wall light: many horizons cut it
  } else {
    lights.push_back(disk_light({0.3, 1.0, -0.2}, {0.1, -1, 0.2}, 1.4));
    lights.push_back(disk_light({-1.5, 0.3, 1.0}, {1, -0.3, 0}, 1.1));
  }
  lights[1].color = {0.5, 0.5, 0.5};
  return lights;
}

}  // namespace phongcl::testing
