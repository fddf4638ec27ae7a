#include "stability/accuracy_bars.h"

#include <cmath>
#include <limits>
#include <random>

#include "common/error.h"
#include "stability/exact_error.h"
#include "stability/gbuffer_builder.h"

namespace phongcl {

namespace {

glm::dvec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  return glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
}

// Any unit vector perpendicular to `axis`, at a random angle around it.
glm::dvec3 random_perpendicular(const glm::dvec3& axis, std::mt19937& rng) {
  return glm::normalize(glm::cross(axis, random_direction(rng)));
}

}  // namespace

std::pair<Scene, GBuffer> far_from_origin_scene(double distance, unsigned seed, int size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);
  const glm::dvec3 centre = distance * random_direction(rng);

  Scene scene;
  scene.camera.eye = centre + glm::dvec3(0.3, 1.7, 6.2);
  scene.ambient = {0.05, 0.04, 0.03};
  for (int i = 0; i < 3; ++i) {
    scene.lights.push_back({LightType::point, centre + 4.0 * glm::dvec3(unit(rng), 1.0 + unit(rng), unit(rng)), {},
                            glm::dvec3(0.4 + zero_one(rng), 0.4 + zero_one(rng), 0.4 + zero_one(rng))});
  }
  scene.lights.push_back({LightType::directional, {}, glm::dvec3(-0.3, -1.0, -0.4), {0.3, 0.3, 0.3}});
  for (int m = 0; m < 4; ++m) {
    scene.materials.push_back({"m" + std::to_string(m), glm::dvec3(0.3), glm::dvec3(0.2 + 0.6 * zero_one(rng)),
                               glm::dvec3(0.2 + 0.6 * zero_one(rng)), std::pow(1000.0, zero_one(rng))});
  }

  GBuffer gbuffer = blank_gbuffer(size, size, "far-from-origin-" + std::to_string(seed));
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    const glm::dvec3 offset(2.0 * unit(rng), 2.0 * unit(rng), 2.0 * unit(rng));
    const glm::dvec3 towards_eye = glm::normalize(scene.camera.eye - (centre + offset));
    const glm::dvec3 normal = glm::normalize(towards_eye + 0.9 * random_direction(rng));
    set_surface(gbuffer, i, glm::vec3(centre + offset), glm::vec3(normal), static_cast<float>(rng() % 4));
  }
  return {scene, gbuffer};
}

std::pair<Scene, GBuffer> highlight_peak_scene(unsigned seed, int size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);

  Scene scene;
  scene.camera.eye = {0.37, 1.13, 5.9};
  scene.lights.push_back({LightType::point, {2.3, 3.1, 4.7}, {}, {1.0, 1.0, 1.0}});
  scene.materials.push_back({"unused: every pixel has its own material", {}, {}, {}, 1.0});

  GBuffer gbuffer = blank_gbuffer(size, size, "highlight-peak-" + std::to_string(seed));
  add_per_pixel_materials(gbuffer);
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    const glm::vec3 position(glm::dvec3(2.0 * unit(rng), 2.0 * unit(rng), 2.0 * unit(rng)));
    const glm::dvec3 p(position);
    const glm::dvec3 v = glm::normalize(scene.camera.eye - p);
    const glm::dvec3 l = glm::normalize(scene.lights[0].position - p);
    const glm::dvec3 half_vector = glm::normalize(v + l);
    const double shininess = std::pow(10.0, 2.0 + 4.0 * zero_one(rng));
    const double turn = 4.0 * zero_one(rng) / (2.0 * std::sqrt(shininess));
    const glm::dvec3 normal = std::cos(turn) * half_vector + std::sin(turn) * random_perpendicular(half_vector, rng);
    // Normals of any length are allowed: the kernel normalises them too.
    set_surface(gbuffer, i, position, glm::vec3(normal * std::pow(2.0, unit(rng))));
    set_material(gbuffer, i, 0.0f, 0.0f, 1.0f, static_cast<float>(shininess));
  }
  return {scene, gbuffer};
}

std::vector<BarFigure> measure_accuracy_bars(PhongShader& shader, int seeds, int size) {
  using Maker = std::pair<Scene, GBuffer> (*)(unsigned seed, int size);
  const std::pair<std::string, Maker> bars[] = {
      {"far from the origin (1e6)", [](unsigned seed, int n) { return far_from_origin_scene(1e6, seed, n); }},
      {"far from the origin (1e7)", [](unsigned seed, int n) { return far_from_origin_scene(1e7, seed, n); }},
      {"highlight peak (q 1e2 to 1e6)", &highlight_peak_scene},
  };
  std::vector<BarFigure> figures;
  for (const auto& [name, make] : bars) {
    for (Precision precision : all_precisions()) {
      if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
      BarFigure figure{name, precision, 0.0, 0, precision == Precision::precise};
      for (int seed = 1; seed <= seeds; ++seed) {
        const auto [scene, gbuffer] = make(static_cast<unsigned>(seed), size);
        try {
          const ShadeResult result = shader.shade(scene, gbuffer, {precision});
          const ExactComparison comparison = compare_with_exact(result.image, scene, gbuffer, kBarAbsolute);
          figure.max_rel = std::max(figure.max_rel, comparison.max_rel);
          figure.nan_values += comparison.nan_values;
        } catch (const InputError&) {
          if (precision != Precision::half_storage) throw;
          figure.max_rel = std::numeric_limits<double>::infinity();  // refused: beyond half's range
        }
      }
      figures.push_back(figure);
    }
  }
  return figures;
}

}  // namespace phongcl
