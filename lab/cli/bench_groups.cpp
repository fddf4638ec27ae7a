// phongcl bench --groups: what light groups cost. The scene's geometry at 1920x1080 (generated from
// its camera) under 16 point lights, shaded with the terms (--aov) three ways: the 16 lights in 4
// groups of 4, the same 16 without groups, and without groups or terms; kernel and download times
// apart (profiling events and the download's wall clock, as ShadeTimings has them), medians of
// --runs after one untimed warm-up each, the variants taking turns.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cl/compute_context.h"
#include "cl/device.h"
#include "cli/bench_arguments.h"
#include "raycast/raycast.h"
#include "report/statistics.h"
#include "shading/phong_shader.h"

namespace phongcl::cli {

namespace {

constexpr int kGroups = 4, kLightsPerGroup = 4;

// 16 point lights on a ring above the scene's look-at point, facing it from every side.
std::vector<Light> ring_of_lights(const Scene& scene, bool grouped) {
  std::vector<Light> lights;
  const glm::dvec3 centre = scene.camera.look_at;
  const double radius = 2.0 * glm::length(scene.camera.eye - centre);
  for (int i = 0; i < kGroups * kLightsPerGroup; ++i) {
    const double angle = 2.0 * 3.14159265358979323846 * i / (kGroups * kLightsPerGroup);
    Light light;
    light.position = centre + glm::dvec3(radius * std::cos(angle), 0.5 * radius, radius * std::sin(angle));
    light.color = glm::dvec3(0.1 + 0.05 * (i % 3), 0.1, 0.1 + 0.05 * (i % 2));
    if (grouped) light.group = "g" + std::to_string(i / kLightsPerGroup);
    lights.push_back(light);
  }
  return lights;
}

// One variant's shader, recipe and images: each keeps its kernel, tables and packed G-buffer.
struct Variant {
  const char* name;
  Scene scene{};
  Recipe recipe{};
  Image image{};
  TermImages terms{};
  FrameTargets targets{};
  std::unique_ptr<PhongShader> shader{};
  std::vector<double> kernel_ms{}, download_ms{};
};

void prepare(Variant& v, const GBuffer& gbuffer, bool terms, const ComputeContext& compute, ProgramCache& cache) {
  ShadeOptions options;
  options.write_terms = terms;
  v.recipe = make_recipe(v.scene, gbuffer, compute.device.info, options);
  v.image = image_like(gbuffer);
  v.terms = {image_like(gbuffer), image_like(gbuffer), image_like(gbuffer), v.recipe.light_groups,
             std::vector<Image>(v.recipe.light_groups.size(), image_like(gbuffer))};
  v.targets = {v.image.pixel(0)};
  if (terms) {
    v.targets = {v.image.pixel(0), v.terms.ambient.pixel(0), v.terms.diffuse.pixel(0), v.terms.specular.pixel(0)};
    for (Image& group : v.terms.groups) v.targets.groups.push_back(group.pixel(0));
  }
  v.shader = std::make_unique<PhongShader>(compute, cache);
  v.shader->shade_into(v.scene, gbuffer, v.recipe, v.targets);  // warm-up: build, pack, upload
}

}  // namespace

void run_groups_bench(const BenchArguments& args) {
  Scene scene = args.inputs.load_scene();
  scene.camera.width = 1920;
  scene.camera.height = 1080;
  const GBuffer gbuffer = generate_gbuffer(scene);
  ProgramCache cache(ProgramCache::default_directory());
  const ComputeContext compute = make_compute_context(pick_device(args.device));
  std::ifstream loadavg("/proc/loadavg");
  std::string load;
  std::getline(loadavg, load);
  std::printf("phongcl bench --groups: %dx%d, %d point lights, %s; medians of %d runs after a warm-up; load %s\n",
              gbuffer.width, gbuffer.height, kGroups * kLightsPerGroup, describe(compute.device.info).c_str(),
              args.runs, load.c_str());
  // The variants take turns run by run, so that a change of the machine's load falls on all three.
  Variant variants[] = {{"4 groups of 4, terms"}, {"no groups, terms"}, {"no groups, no terms"}};
  const bool grouped[] = {true, false, false}, terms[] = {true, true, false};
  for (int v = 0; v < 3; ++v) {
    variants[v].scene = scene;
    variants[v].scene.lights = ring_of_lights(scene, grouped[v]);
    prepare(variants[v], gbuffer, terms[v], compute, cache);
  }
  for (int r = 0; r < args.runs; ++r)
    for (Variant& v : variants) {
      const ShadeReport report = v.shader->shade_into(v.scene, gbuffer, v.recipe, v.targets);
      v.kernel_ms.push_back(report.timings.kernel_ms);
      v.download_ms.push_back(report.timings.download_ms);
    }
  std::printf("  %-22s %10s %12s\n", "variant", "kernel ms", "download ms");
  for (const Variant& v : variants)
    std::printf("  %-22s %10.2f %12.2f\n", v.name, median(v.kernel_ms), median(v.download_ms));
  std::printf("  groups against none (both with terms): kernel x%.2f, download x%.2f\n",
              median(variants[0].kernel_ms) / median(variants[1].kernel_ms),
              median(variants[0].download_ms) / median(variants[1].download_ms));
}

}  // namespace phongcl::cli
