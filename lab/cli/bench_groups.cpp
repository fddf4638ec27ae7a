// phongcl bench --groups: what light groups cost. The scene's geometry at 1920x1080 (generated from
// its camera) under 16 point lights, shaded with the terms (--aov) three ways: the 16 lights in 4
// groups of 4, the same 16 without groups, and without groups or terms; kernel and download times
// apart (profiling events and the download's wall clock, as ShadeTimings has them), medians of
// --runs after one untimed warm-up.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
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

struct GroupTimes {
  double kernel_ms, download_ms;
};

GroupTimes time_variant(PhongShader& shader, const Scene& scene, const GBuffer& gbuffer, bool terms, int runs) {
  ShadeOptions options;
  options.write_terms = terms;
  const Recipe recipe = make_recipe(scene, gbuffer, shader.compute().device.info, options);
  Image image = image_like(gbuffer);
  TermImages images{image_like(gbuffer), image_like(gbuffer), image_like(gbuffer), recipe.light_groups,
                    std::vector<Image>(recipe.light_groups.size(), image_like(gbuffer))};
  FrameTargets targets{image.pixel(0)};
  if (terms) {
    targets = {image.pixel(0), images.ambient.pixel(0), images.diffuse.pixel(0), images.specular.pixel(0)};
    for (Image& group : images.groups) targets.groups.push_back(group.pixel(0));
  }
  shader.forget_gbuffer();
  shader.forget_uniforms();
  shader.shade_into(scene, gbuffer, recipe, targets);  // warm-up: build, pack, upload
  std::vector<double> kernel, download;
  for (int r = 0; r < runs; ++r) {
    const ShadeReport report = shader.shade_into(scene, gbuffer, recipe, targets);
    kernel.push_back(report.timings.kernel_ms);
    download.push_back(report.timings.download_ms);
  }
  return {median(kernel), median(download)};
}

}  // namespace

void run_groups_bench(const BenchArguments& args) {
  Scene scene = args.inputs.load_scene();
  scene.camera.width = 1920;
  scene.camera.height = 1080;
  const GBuffer gbuffer = generate_gbuffer(scene);
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  std::ifstream loadavg("/proc/loadavg");
  std::string load;
  std::getline(loadavg, load);
  std::printf("phongcl bench --groups: %dx%d, %d point lights, %s; medians of %d runs after a warm-up; load %s\n",
              gbuffer.width, gbuffer.height, kGroups * kLightsPerGroup, describe(shader.compute().device.info).c_str(),
              args.runs, load.c_str());
  struct Variant {
    const char* name;
    bool grouped, terms;
  };
  const Variant variants[] = {{"4 groups of 4, terms", true, true},
                              {"no groups, terms", false, true},
                              {"no groups, no terms", false, false}};
  std::printf("  %-22s %10s %12s\n", "variant", "kernel ms", "download ms");
  std::vector<GroupTimes> times;
  for (const Variant& variant : variants) {
    scene.lights = ring_of_lights(scene, variant.grouped);
    times.push_back(time_variant(shader, scene, gbuffer, variant.terms, args.runs));
    std::printf("  %-22s %10.2f %12.2f\n", variant.name, times.back().kernel_ms, times.back().download_ms);
  }
  std::printf("  groups against none (both with terms): kernel x%.2f, download x%.2f\n",
              times[0].kernel_ms / times[1].kernel_ms, times[0].download_ms / times[1].download_ms);
}

}  // namespace phongcl::cli
