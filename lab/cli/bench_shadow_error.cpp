// phongcl bench --shadows, the error-against-run-time part: on each scene (--scene's, scenes/spotlights,
// scenes/large with 16 lights, a knot mesh), every light casting shadows, the kernel with exact
// geometry shadows, without shadows, and with screen-space shadows at 8 to 128 steps and three
// thicknesses, timed round-robin (drifting load falls on every variant alike); each image compared
// with the exact one; then the same scene's shadow rays alone, traversing the BVH against tiled
// shadow culling.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "cl/compute_context.h"
#include "cli/bench_arguments.h"
#include "cli/shadow_bench_report.h"
#include "cli/shadow_image_error.h"
#include "geometry/device_geometry.h"
#include "geometry/scene_bvh.h"
#include "peers/light_sweep.h"
#include "peers/opencl_shadow_rays.h"
#include "peers/packed_frame.h"
#include "raycast/raycast.h"
#include "report/statistics.h"
#include "shading/phong_shader.h"

namespace phongcl::cli {

namespace {

// A pixel's shadows differ when the two images differ there by more than this fraction of the
// unshadowed pixel (largest channel): a light's shadow decided otherwise changes the pixel by that
// light's whole contribution, rounding by 1e-6 of it.
constexpr double kDifferentShadows = 0.01;

const int kSteps[] = {8, 16, 32, 64, 128};
const char* const kThicknesses[] = {"2%", "6%", "20%"};

struct BenchScene {
  std::string name;
  Scene scene;
  GBuffer gbuffer;
};

Scene casting_every_light(Scene scene) {
  for (Light& light : scene.lights) light.shadows = true;
  return scene;
}

// A scene whose G-buffer is not in the repository (scenes/large) is ray-cast.
BenchScene loaded(const SceneInputs& inputs, int lights = 0) {
  Scene scene = inputs.load_scene();
  GBuffer gbuffer =
      std::filesystem::exists(inputs.gbuffer_path(scene)) ? inputs.load_gbuffer(scene) : generate_gbuffer(scene);
  if (lights > 0) scene = with_generated_lights(scene, lights);
  const std::string label = std::filesystem::path(inputs.scene_file).parent_path().filename().string() + " (" +
                            std::to_string(scene.lights.size()) + " lights)";
  return {label, casting_every_light(std::move(scene)), std::move(gbuffer)};
}

BenchScene bundled(const std::string& name, int lights = 0) {
  SceneInputs inputs;
  inputs.scene_file = "scenes/" + name + "/scene.json";
  if (!std::filesystem::exists(inputs.scene_file))
    throw std::runtime_error("bench --shadows: no " + inputs.scene_file + " (run it from the repository root)");
  return loaded(inputs, lights);
}

ShadowSceneResult measure(PhongShader& shader, const BenchScene& bench, int runs) {
  ShadowSceneResult result;
  result.name = bench.name;
  result.width = bench.gbuffer.width;
  result.height = bench.gbuffer.height;
  result.lights = static_cast<int>(bench.scene.lights.size());
  std::vector<ShadeOptions> options;
  auto add = [&](const std::string& label, const ShadowSettings& settings, const std::string& thickness = "") {
    ShadowVariant& variant = result.variants.emplace_back();
    variant.label = label;
    variant.mode = to_string(settings.mode);
    if (settings.mode == ShadowMode::screen) variant.steps = settings.steps, variant.thickness = thickness;
    ShadeOptions option;
    option.shadows = settings;
    options.push_back(option);
  };
  add("geometry", {ShadowMode::geometry});
  add("off", {ShadowMode::off});
  for (const char* thickness : kThicknesses)
    for (int steps : kSteps)
      add("screen " + std::to_string(steps) + " steps, " + thickness,
          {ShadowMode::screen, steps, parse_shadow_thickness(thickness)}, thickness);

  // The untimed warm-up builds each program; its image is the one compared.
  std::vector<Image> images;
  for (const ShadeOptions& option : options) {
    ShadeResult shaded = shader.shade(bench.scene, bench.gbuffer, option);
    if (option.shadows.mode == ShadowMode::geometry) result.geometry = shaded.shadows;
    images.push_back(std::move(shaded.image));
  }
  for (std::size_t i = 0; i < bench.gbuffer.pixel_count(); ++i)
    result.shaded += classify_pixel(bench.gbuffer, i) == PixelClass::shaded;
  for (std::size_t v = 0; v < options.size(); ++v) {
    const ShadowImageError error = shadow_image_error(images[v], images[0], images[1], bench.gbuffer, kDifferentShadows);
    result.variants[v].mismatch = error.beyond;
    result.variants[v].mean_abs_error = error.mean_abs_error;
  }
  std::vector<std::vector<double>> times(options.size());
  for (int run = 0; run < runs; ++run)
    for (std::size_t v = 0; v < options.size(); ++v)
      times[v].push_back(shader.shade(bench.scene, bench.gbuffer, options[v]).timings.kernel_ms);
  for (std::size_t v = 0; v < options.size(); ++v) result.variants[v].kernel_ms = median(times[v]);
  return result;
}

// Every ray traversing, then tiled culling at 8, 16 and 32 pixels, timed round-robin; the counts
// of blocked lights compared with the traversal's (culling only leaves out what cannot block).
std::vector<ShadowCullingVariant> measure_culling(const ComputeContext& compute, ProgramCache& cache,
                                                  const BenchScene& bench, int runs) {
  using Method = OpenClShadowRays::Method;
  const glm::dvec3 eye = bench.scene.camera.eye;
  const SceneBvh bvh = build_scene_bvh(flatten_objects(bench.scene.objects), PHONGCL_BVH_MAX_DEPTH);
  OpenClShadowRays tracer(compute, cache, pack_device_geometry(bvh, eye));
  tracer.set_frame(pack_frame(bench.gbuffer, bench.scene), bench.gbuffer.width, bench.gbuffer.height, bench.scene, eye,
                   PHONGCL_SHADOW_OFFSET_FLOAT);
  std::vector<ShadowCullingVariant> variants;
  for (int tile : {0, 8, 16, 32}) variants.push_back({.tile = tile});
  auto count = [&](const ShadowCullingVariant& v) {
    return tracer.count_blocked(v.tile == 0 ? Method::traverse : Method::culled, std::max(v.tile, 1));
  };
  std::vector<float> traversed;
  for (ShadowCullingVariant& v : variants) {  // the warm-up builds the programs
    const OpenClShadowRays::Counts counts = count(v);
    if (v.tile == 0) traversed = counts.blocked_lights;
    v.candidates_per_pair = counts.candidates_per_pair;
    v.traversing_pairs = counts.traversing_pairs;
    for (std::size_t i = 0; i < traversed.size(); ++i) v.differing += counts.blocked_lights[i] != traversed[i];
  }
  std::vector<std::vector<double>> totals(variants.size()), culling(variants.size());
  for (int run = 0; run < runs; ++run)
    for (std::size_t k = 0; k < variants.size(); ++k) {
      const OpenClShadowRays::Counts counts = count(variants[k]);
      totals[k].push_back(counts.culling_ms + counts.kernel_ms);
      culling[k].push_back(counts.culling_ms);
    }
  for (std::size_t k = 0; k < variants.size(); ++k) {
    variants[k].total_ms = median(totals[k]);
    variants[k].culling_ms = median(culling[k]);
  }
  return variants;
}

}  // namespace

std::vector<ShadowSceneResult> run_shadow_error_bench(const BenchArguments& args, const std::filesystem::path& scratch) {
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  std::vector<BenchScene> scenes;
  scenes.push_back(loaded(args.inputs));
  scenes.push_back(bundled("spotlights"));
  scenes.push_back(bundled("large", 16));
  Scene knot = mesh_scene(scratch, args.mesh_triangles, 4, 960, 540);
  GBuffer knot_gbuffer = generate_gbuffer(knot);
  scenes.push_back({"knot mesh (" + std::to_string(knot.lights.size()) + " lights)", casting_every_light(std::move(knot)),
                    std::move(knot_gbuffer)});
  std::vector<ShadowSceneResult> results;
  for (const BenchScene& scene : scenes) {
    std::cout << "  scene      " << scene.name << ", " << scene.gbuffer.width << "x" << scene.gbuffer.height << "..."
              << std::flush;
    results.push_back(measure(shader, scene, args.runs));
    std::cout << " " << results.back().geometry << "\n\n" << shadow_error_table(results.back()) << "\n" << std::flush;
    results.back().culling = measure_culling(shader.compute(), cache, scene, args.runs);
    std::cout << shadow_culling_table(results.back()) << "\n";
  }
  return results;
}

}  // namespace phongcl::cli
