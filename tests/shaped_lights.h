#pragma once
// Random falloff, ranges, spots and light linking for the light-shape and culling suites.
#include <cmath>
#include <random>

#include "scene/scene.h"

namespace phongcl::testing {

struct ShapedLightSpec {
  int lights = 6;
  bool falloff = true, mixed_falloff = false, range = true, spots = true, hard_spots = false, linking = false;
  double max_cosine_power = 0.0;  // spots get a cosine power p in [0, max): every other one 0
  double min_range = 2.0, max_range = 8.0;
};

// Lights at distance 2 to 6 from the origin (where random_scene's surface points are), spots
// aimed near it with cones of 20-100 degrees and penumbras of 5-20 (0 for hard_spots).
inline void add_shaped_lights(Scene& scene, const ShapedLightSpec& spec, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);
  auto direction = [&] { return glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)) + glm::dvec3(0.0, 0.0, 1e-3)); };
  const int materials = static_cast<int>(scene.materials.size());
  for (int i = 0; i < spec.lights; ++i) {
    Light light;
    light.type = spec.spots && i % 2 == 0 ? LightType::spot : LightType::point;
    light.position = direction() * (2.0 + 4.0 * zero_one(rng));
    light.color = glm::dvec3(zero_one(rng), zero_one(rng), zero_one(rng)) * 2.0;
    if (spec.falloff) light.falloff = spec.mixed_falloff ? static_cast<Falloff>(i % 4) : Falloff::quadratic;
    if (spec.range) light.range = spec.min_range + (spec.max_range - spec.min_range) * zero_one(rng);
    if (light.type == LightType::spot) {
      light.direction = glm::normalize(-light.position + 0.5 * direction());
      light.cone_angle_deg = 20.0 + 80.0 * zero_one(rng);
      light.penumbra_angle_deg = spec.hard_spots ? 0.0 : 5.0 + 15.0 * zero_one(rng);
      if (spec.max_cosine_power > 0.0 && i % 4 == 0) light.cosine_power = spec.max_cosine_power * zero_one(rng);
    }
    if (spec.linking && materials > 0) {
      std::vector<int> linked;
      for (int m = 0; m < materials; ++m)
        if ((rng() & 1) != 0) linked.push_back(m);
      light.materials = linked;
    }
    scene.lights.push_back(light);
  }
}

// Pixels within 1e-5 of a hard-edged spot's cone edge: there the float dot product (error ~1e-7)
// may land on the other side of the discontinuity than the double one.
inline std::vector<bool> away_from_hard_edges(const Scene& scene, const GBuffer& gbuffer, std::vector<bool> mask) {
  for (const Light& light : scene.lights) {
    if (light.type != LightType::spot || light.penumbra_angle_deg > 0.0) continue;
    const double inner = std::cos(light.cone_angle_deg / 2.0 * 3.14159265358979323846 / 180.0);
    for (std::size_t i = 0; i < mask.size(); ++i) {
      const glm::dvec3 p(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]);
      const double c = glm::dot(glm::normalize(p - light.position), glm::normalize(light.direction));
      if (std::abs(c - inner) < 1e-5) mask[i] = false;
    }
  }
  return mask;
}

}  // namespace phongcl::testing
