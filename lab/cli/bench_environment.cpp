// phongcl bench --environment: scenes/large at 480x270 lit by a uniform white world alone, its
// visibility traced with 1, 4, 16, 64 and 256 cosine-distributed rays per pixel and with 4096, the
// converged estimate each image is compared with (its error at most 1/(2 sqrt 4096) = 0.8% of the
// light); then screen space (horizons of slices x steps a side found in the depth plane) against the
// geometry's 4096. Timed round-robin, medians of the kernel's profiling events (the kernel's build and the
// transfers not included).
#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>

#include "cl/compute_context.h"
#include "cli/bench_arguments.h"
#include "cli/shadow_image_error.h"
#include "raycast/raycast.h"
#include "report/statistics.h"
#include "shading/phong_shader.h"

namespace phongcl::cli {

namespace {

constexpr int kEnvironmentConvergedRays = 4096;
// A pixel agrees when within this fraction of its unoccluded value, as the Cycles checks count.
constexpr double kEnvironmentAgreement = 0.05;

struct EnvironmentVariant {
  std::string label;
  ShadeOptions options;
  double agreement = 0.0, mean_abs_error = 0.0;
};

}  // namespace

void run_environment_bench(const BenchArguments& args) {
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  Scene scene = load_scene("scenes/large/scene.json");
  scene.lights.clear();
  scene.ambient = glm::dvec3(0.0);
  scene.environment = EnvironmentLight{};
  scene.camera.width = 480;  // rendered at this size: screen space needs the camera that made the G-buffer
  scene.camera.height = 270;
  const GBuffer gbuffer = generate_gbuffer(scene);

  std::vector<EnvironmentVariant> variants;
  auto add = [&](const std::string& label, ShadowMode mode, int rays, int steps = ShadowSettings{}.steps) {
    EnvironmentVariant variant{label, {}};
    variant.options.shadows.mode = mode;
    variant.options.shadows.environment_rays = rays;
    variant.options.shadows.steps = steps;
    variants.push_back(variant);
  };
  add("unoccluded", ShadowMode::off, 1);
  for (int rays : {1, 4, 16, 64, 256}) add("geometry, " + std::to_string(rays) + (rays == 1 ? " ray" : " rays"), ShadowMode::geometry, rays);
  add("geometry, " + std::to_string(kEnvironmentConvergedRays) + " rays", ShadowMode::geometry, kEnvironmentConvergedRays);
  for (auto [slices, steps] : {std::pair{4, 8}, {8, 16}, {16, 32}, {64, 32}})
    add("screen, " + std::to_string(slices) + " slices x " + std::to_string(steps) + " steps", ShadowMode::screen, slices, steps);
  const std::size_t converged_index = 6;
  std::cout << "\nEnvironment: scenes/large, 480x270, a uniform white world alone\n" << std::flush;

  std::vector<Image> images;  // the untimed warm-up builds each program
  for (const EnvironmentVariant& variant : variants) images.push_back(shader.shade(scene, gbuffer, variant.options).image);
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const ShadowImageError error =
        shadow_image_error(images[v], images[converged_index], images.front(), gbuffer, kEnvironmentAgreement);
    variants[v].agreement = 1.0 - error.beyond;
    variants[v].mean_abs_error = error.mean_abs_error;
  }
  std::vector<std::vector<double>> times(variants.size());
  for (int round = 0; round < args.runs; ++round)
    for (std::size_t v = 0; v < variants.size(); ++v)
      times[v].push_back(shader.shade(scene, gbuffer, variants[v].options).timings.kernel_ms);
  std::ostringstream table;
  table << "| visibility | agreement with " << kEnvironmentConvergedRays << " geometry rays (within 5%) | mean abs error | kernel ms |\n"
        << "|---|--:|--:|--:|\n";
  for (std::size_t v = 0; v < variants.size(); ++v) {
    char line[200];
    std::snprintf(line, sizeof line, "| %s | %.2f%% | %.2e | %.1f |\n", variants[v].label.c_str(),
                  100.0 * variants[v].agreement, variants[v].mean_abs_error, median(times[v]));
    table << line;
  }
  std::cout << "\n" << table.str();
}

}  // namespace phongcl::cli
