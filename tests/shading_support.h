#pragma once
// Shared by the kernel test suites: the default OpenCL device (opencl_required.h where there is none),
// seeded random scenes and G-buffers, and a reference comparison that names the worst pixel.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <sstream>

#include "accuracy_bound.h"
#include "cl/device.h"
#include "opencl_required.h"
#include "raycast/raycast.h"
#include "reference/reference.h"
#include "shading/phong_shader.h"

namespace phongcl::testing {

// One context and in-memory program cache for the whole test binary: building contexts and
// programs is the slow part, and sharing them is what the CLI does within one run too.
inline PhongShader* shared_shader() {
  static std::unique_ptr<ProgramCache> cache;
  static std::unique_ptr<PhongShader> shader;
  static bool tried = false;
  if (!tried) {
    tried = true;
    if (!list_devices().empty()) {
      cache = std::make_unique<ProgramCache>(std::filesystem::path());
      shader = std::make_unique<PhongShader>(make_compute_context(pick_device("")), *cache);
    }
  }
  return shader.get();
}

// In a TEST body: PHONGCL_REQUIRE_DEVICE(shader); declares `PhongShader& shader`, or returns as
// PHONGCL_REQUIRE_OPENCL says on a machine without an OpenCL device (opencl_required.h).
#define PHONGCL_REQUIRE_DEVICE(name)                                              \
  PhongShader* name##_or_null = ::phongcl::testing::shared_shader();              \
  PHONGCL_REQUIRE_OPENCL(name##_or_null != nullptr);                              \
  PhongShader& name = *name##_or_null

struct RandomSceneSpec {
  int width = 37, height = 23;  // prime sizes: no work-group size divides them
  int point_lights = 3, directional_lights = 2;
  int materials = 4;
  double max_shininess = 1000.0;
  bool per_pixel_materials = false;
  double background_fraction = 0.2;
};

// A random scene and a G-buffer of random surface points in front of the eye, normals of random
// length (1e-3 to 1e3) that mostly face the eye, some background pixels.
inline std::pair<Scene, GBuffer> random_scene(const RandomSceneSpec& spec, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);
  auto random_color = [&](double scale) { return glm::dvec3(zero_one(rng), zero_one(rng), zero_one(rng)) * scale; };

  Scene scene;
  scene.camera.eye = {0.3, 1.1, 6.0};
  scene.ambient = random_color(0.2);
  scene.background = {0.05, 0.1, 0.2};
  for (int i = 0; i < spec.point_lights; ++i) {
    scene.lights.push_back({LightType::point, glm::dvec3(unit(rng), unit(rng), unit(rng)) * 6.0, {}, random_color(1.5)});
  }
  for (int i = 0; i < spec.directional_lights; ++i) {
    scene.lights.push_back({LightType::directional, {}, glm::dvec3(unit(rng), unit(rng) - 0.5, unit(rng)), random_color(1.0)});
  }
  for (int i = 0; i < spec.materials; ++i) {
    // Shininess spread on a log scale, so both broad and needle-sharp highlights appear.
    scene.materials.push_back({std::string("m").append(std::to_string(i)), random_color(0.3), random_color(0.9),
                               random_color(0.8), std::pow(spec.max_shininess, zero_one(rng))});
  }

  GBuffer g;
  g.width = spec.width;
  g.height = spec.height;
  g.data_window = g.display_window = PixelWindow{0, 0, spec.width - 1, spec.height - 1};
  const std::size_t n = g.pixel_count();
  for (auto* planes : {&g.position, &g.normal}) for (auto& plane : *planes) plane.resize(n);
  g.material.resize(n);
  if (spec.per_pixel_materials) {
    for (auto* planes : {&g.ka, &g.kd, &g.ks}) for (auto& plane : *planes) plane.resize(n);
    g.shininess.resize(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p(unit(rng) * 2.0, unit(rng) * 2.0, unit(rng) * 2.0);
    glm::dvec3 normal = glm::normalize(glm::normalize(scene.camera.eye - p) + 0.9 * glm::dvec3(unit(rng), unit(rng), unit(rng)));
    normal *= std::pow(10.0, 3.0 * unit(rng));
    for (int c = 0; c < 3; ++c) {
      g.position[c][i] = static_cast<float>(p[c]);
      g.normal[c][i] = static_cast<float>(normal[c]);
    }
    const bool background = zero_one(rng) < spec.background_fraction;
    g.material[i] = background ? -1.0f : static_cast<float>(rng() % std::max(spec.materials, 1));
    if (spec.per_pixel_materials) {
      for (int c = 0; c < 3; ++c) {
        g.ka[c][i] = static_cast<float>(zero_one(rng) * 0.3);
        g.kd[c][i] = static_cast<float>(zero_one(rng));
        g.ks[c][i] = static_cast<float>(zero_one(rng));
      }
      g.shininess[i] = static_cast<float>(std::pow(spec.max_shininess, zero_one(rng)));
    }
  }
  g.source = "random-" + std::to_string(seed);
  return {scene, g};
}

// Where and how the kernel's image differs from the reference, for failure messages.
inline std::string describe_worst(const ErrorStats& stats) {
  std::ostringstream text;
  static const char* channels = "RGB";
  text << "max_rel " << stats.max_rel << ", max_abs " << stats.max_abs << "; worst pixel (" << stats.worst_x << ", "
       << stats.worst_y << ") " << channels[stats.worst_channel] << ": kernel " << stats.worst_test << ", reference "
       << stats.worst_expected << "; non-finite mismatches " << stats.nonfinite_mismatches;
  return text.str();
}

// Shaded pixels only: the relative bound is about shading; background is compared exactly apart.
inline std::vector<bool> shaded_mask(const GBuffer& gbuffer) {
  std::vector<bool> mask(gbuffer.pixel_count());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = classify_pixel(gbuffer, i) == PixelClass::shaded;
  return mask;
}

// The ambient, diffuse and specular images add up to the image on every shaded pixel. The kernel
// sums the three non-negative terms in float (two roundings) and stores each from the same sums,
// so their exact sum is within 2 ulp of the stored value; 4 ulp leaves room for the unscaling.
inline void expect_terms_sum_to_image(const TermImages& terms, const Image& image, const std::vector<bool>& shaded) {
  constexpr double kFourUlp = 4 * 0x1p-24;
  for (const Image* term : {&terms.ambient, &terms.diffuse, &terms.specular})
    ASSERT_EQ(term->pixel_count(), image.pixel_count());
  bool any_specular = false;
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    if (!shaded[i]) continue;  // background: the scene's colour, not a sum of terms
    for (int c = 0; c < 3; ++c) {
      const double sum = double(terms.ambient.pixel(i)[c]) + terms.diffuse.pixel(i)[c] + terms.specular.pixel(i)[c];
      ASSERT_NEAR(sum, image.pixel(i)[c], kFourUlp * std::abs(sum)) << "pixel " << i << ", channel " << c;
      any_specular |= terms.specular.pixel(i)[c] > 0.0f;
    }
    ASSERT_EQ(terms.diffuse.pixel(i)[3], image.pixel(i)[3]) << "alpha of pixel " << i;
  }
  EXPECT_TRUE(any_specular) << "no pixel has a specular term: the sum checks too little";
}

// Background pixels must equal the scene's background colour with alpha 0, exactly; shaded ones alpha 1.
inline void expect_background_exact(const Image& image, const Scene& scene, const GBuffer& gbuffer) {
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    const float* px = image.pixel(i);
    if (classify_pixel(gbuffer, i) == PixelClass::shaded) {
      ASSERT_EQ(px[3], 1.0f) << "alpha of shaded pixel " << i;
      continue;
    }
    for (int c = 0; c < 3; ++c) ASSERT_EQ(px[c], static_cast<float>(scene.background[c])) << "background pixel " << i;
    ASSERT_EQ(px[3], 0.0f) << "alpha of background pixel " << i;
  }
}

}  // namespace phongcl::testing
