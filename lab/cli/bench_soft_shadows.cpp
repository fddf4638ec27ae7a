// phongcl bench --shadows, the soft-shadow part: scenes/large at 480x270 with 16 generated point
// lights (with_generated_lights' 32, less the directional half) as area lights casting shadows, shaded with 1 ray (the hard shadow), 4, 16 and 64, and
// with kSoftReferenceRays, the converged estimate each image is compared with, and in screen space
// with 1, 4, 16 and 64 marches against the same estimate; beside them the
// same scene's 16 point lights with their hard shadows. Timed round-robin, medians of the kernel's
// profiling events (the shadow culling included; the kernel's build, the transfers not).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cl/compute_context.h"
#include "cli/bench_arguments.h"
#include "cli/shadow_bench_report.h"
#include "cli/shadow_image_error.h"
#include "peers/light_sweep.h"
#include "raycast/raycast.h"
#include "report/statistics.h"
#include "shading/phong_shader.h"

namespace phongcl::cli {

namespace {

// The estimate the others are compared with: its penumbra's error is 1/(2 sqrt 1024) = 1.6% of
// the light at most (test_shading_soft_shadows.cpp), a third of the agreement's 5%.
constexpr int kSoftReferenceRays = 1024;
// A pixel agrees when it is within this fraction of its unshadowed value, as the Cycles checks count.
constexpr double kAgreement = 0.05;

// Each point light becomes a square emitter of side 1/8 of its distance to the look-at point,
// facing that point, its colour scaled to light it about as the point did there.
Scene with_area_lights(Scene scene) {
  for (const Light& light : scene.lights) {
    const glm::dvec3 toward = scene.camera.look_at - light.position;
    const double distance = glm::length(toward);
    AreaLight area;
    area.position = light.position;
    area.direction = toward;
    area.up = std::abs(toward.y) < 0.9 * distance ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    area.size = glm::dvec2(distance / 8.0);
    area.color = light.color * (64.0 / (distance * distance));
    area.shadows = true;
    scene.area_lights.push_back(area);
  }
  scene.lights.clear();
  return scene;
}

struct SoftVariant {
  std::string label;
  double kernel_ms = 0.0, agreement = 0.0, mean_abs_error = 0.0;
};

}  // namespace

void run_soft_shadow_bench(const BenchArguments& args) {
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  Scene large = with_generated_lights(load_scene("scenes/large/scene.json"), 32);
  std::erase_if(large.lights, [](const Light& light) { return light.type == LightType::directional; });
  large.ambient = glm::dvec3(0.0);  // the agreement is of the lights' light, as the Cycles checks count it
  // Rendered at 480x270 by its own camera, which screen space's march needs.
  large.camera.width = 480;
  large.camera.height = 270;
  const GBuffer gbuffer = generate_gbuffer(large);
  const Scene soft = with_area_lights(large);
  Scene hard_points = large;
  for (Light& light : hard_points.lights) light.shadows = true;

  struct Run {
    const Scene* scene;
    ShadeOptions options;
    SoftVariant variant;
  };
  std::vector<Run> runs;
  auto add = [&](const Scene& scene, const std::string& label, ShadowMode mode, int rays) {
    ShadeOptions options;
    options.shadows.mode = mode;
    options.shadows.rays = rays;
    runs.push_back({&scene, options, {label}});
  };
  add(soft, "area lights, unshadowed", ShadowMode::off, 1);
  for (int rays : {1, 4, 16, 64, kSoftReferenceRays})
    add(soft, "area lights, " + std::to_string(rays) + (rays == 1 ? " ray (hard)" : " rays"), ShadowMode::geometry, rays);
  const std::size_t converged_run = runs.size() - 1;
  // Screen space's marches, each against the same converged geometry shadows.
  for (int rays : {1, 4, 16, 64})
    add(soft, "area lights, screen, " + std::to_string(rays) + (rays == 1 ? " march (hard)" : " marches"),
        ShadowMode::screen, rays);
  add(hard_points, "point lights, hard (1 ray)", ShadowMode::geometry, 1);
  std::cout << "\nSoft shadows: scenes/large, 480x270, " << soft.area_lights.size()
            << " area lights casting shadows (and the same " << hard_points.lights.size() << " as point lights)\n"
            << std::flush;

  std::vector<Image> images;  // the untimed warm-up builds each program
  for (Run& run : runs) images.push_back(shader.shade(*run.scene, gbuffer, run.options).image);
  const Image& unshadowed = images.front();
  const Image& converged = images[converged_run];
  for (std::size_t v = 0; v + 1 < runs.size(); ++v) {
    const ShadowImageError error = shadow_image_error(images[v], converged, unshadowed, gbuffer, kAgreement);
    runs[v].variant.agreement = 1.0 - error.beyond;
    runs[v].variant.mean_abs_error = error.mean_abs_error;
  }
  std::vector<std::vector<double>> times(runs.size());
  for (int round = 0; round < args.runs; ++round)
    for (std::size_t v = 0; v < runs.size(); ++v)
      times[v].push_back(shader.shade(*runs[v].scene, gbuffer, runs[v].options).timings.kernel_ms);
  std::ostringstream table;
  table << "| shadows | agreement with " << kSoftReferenceRays << " rays (within 5%) | mean abs error | kernel ms |\n"
        << "|---|--:|--:|--:|\n";
  for (std::size_t v = 0; v < runs.size(); ++v) {
    const SoftVariant& variant = runs[v].variant;
    char line[200];
    if (v + 1 < runs.size())
      std::snprintf(line, sizeof line, "| %s | %.2f%% | %.2e | %.1f |\n", variant.label.c_str(), 100.0 * variant.agreement,
                    variant.mean_abs_error, median(times[v]));
    else
      std::snprintf(line, sizeof line, "| %s | | | %.1f |\n", variant.label.c_str(), median(times[v]));
    table << line;
  }
  std::cout << "\n" << table.str();
}

}  // namespace phongcl::cli
