// phongcl shade: the OpenCL kernel on a G-buffer.
#include <chrono>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>

#include <phongcl/relighter.hpp>

#include "cli/commands.h"
#include "cli/format.h"
#include "cli/inputs.h"
#include "cli/outputs.h"
#include "cli/shade_over.h"
#include "cli/shade_sequence.h"
#include "exr/exr_channels.h"

namespace phongcl::cli {

namespace {

struct ShadeArguments {
  SceneInputs inputs;
  ImageOutputs outputs;
  std::string device;
  std::string precision = "precise";
  bool no_specialise = false;
  int lanes = 0;
  std::string culling = "auto";
  int tile = 16;
  std::string shadows = "auto";
  int shadow_steps = ShadowSettings{}.steps;
  int shadow_rays = ShadowSettings{}.rays;
  int environment_rays = ShadowSettings{}.environment_rays;
  std::string shadow_thickness = format_shadow_thickness(ShadowSettings{}.thickness);
  bool explain = false;
  std::string over;  // a render to composite over (cli/shade_over.h)
  SequenceOptions sequence;
};

void print_unshaded(const PixelCounts& counts) {
  auto line = [](std::size_t count, const char* what) {
    if (count > 0) std::cout << "  note       " << with_commas(count) << " pixels had non-finite " << what << " and were left unshaded\n";
  };
  line(counts.nonfinite_position, "positions");
  line(counts.nonfinite_normal, "normals");
  line(counts.nonfinite_material, "material values");
}

using Clock = std::chrono::steady_clock;
double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

RelighterOptions relighter_options(const ShadeArguments& args) {
  RelighterOptions options{args.device, parse_precision(args.precision), !args.no_specialise, args.lanes};
  options.culling = parse_culling(args.culling);
  options.tile_size = args.tile;
  options.terms = args.outputs.wants_terms() || !args.over.empty();
  options.shadows = {parse_shadow_mode(args.shadows), args.shadow_steps, parse_shadow_thickness(args.shadow_thickness),
                     args.shadow_rays, args.environment_rays};
  check_options(options);
  return options;
}

void run_shade(const ShadeArguments& args) {
  const RelighterOptions options = relighter_options(args);  // checked before anything is read
  if (args.sequence.wanted(args.inputs, args.outputs)) {
    if (!args.over.empty()) throw std::invalid_argument("--over composites one frame over one render, not a sequence");
    run_shade_sequence(args.inputs, args.outputs, options, args.sequence);
    return;
  }
  const std::vector<NamedFile> over = args.over.empty() ? std::vector<NamedFile>{} : std::vector<NamedFile>{{"--over", args.over}};
  const auto start = Clock::now();
  ImageOutputs outputs = args.outputs;
  outputs.color = args.inputs.color_config();
  refuse_outputs_over_inputs(args.inputs, outputs, nullptr, over);
  outputs.check_destinations();
  args.sequence.start_exr_threads();
  // The G-buffer is read while the OpenCL platform starts: neither needs the other. OpenCL stays on
  // this thread: Oclgrind's memory checks keep per-thread state and crash on calls from another.
  struct Inputs {
    Scene scene;
    LoadedGBuffer loaded;
    double read_ms = 0.0;
  };
  std::future<Inputs> reading = std::async(std::launch::async, [&] {
    Scene scene = args.inputs.load_scene();
    refuse_outputs_over_inputs(args.inputs, outputs, &scene, over);
    LoadedGBuffer loaded = args.inputs.load_described_gbuffer(scene);
    return Inputs{std::move(scene), std::move(loaded), milliseconds_since(start)};
  });
  Relighter relighter(options);
  Inputs inputs = reading.get();
  const Scene& scene = inputs.scene;
  const LoadedGBuffer& loaded = inputs.loaded;
  const double read_ms = inputs.read_ms;
  relighter.set_frame(scene, std::move(inputs.loaded.gbuffer));
  const GBuffer& gbuffer = relighter.gbuffer();
  TermImages terms;
  // --over shades its groups itself (composite/relight_over.h): terms here only for --aov.
  const Image shaded = args.outputs.wants_terms() ? relighter.shade(terms) : relighter.shade();
  const ShadeReport result = relighter.last_report();
  const auto composite_start = Clock::now();
  const OverResult composite = args.over.empty() ? OverResult{} : shade_over(args.over, scene, relighter);
  const double composite_ms = milliseconds_since(composite_start);
  const Image& image = args.over.empty() ? shaded : composite.image;
  const auto write_start = Clock::now();
  outputs.compression = args.sequence.output_compression(gbuffer.compression);
  const std::string written = outputs.write(image, scene.background, terms);
  const double write_ms = milliseconds_since(write_start);

  const ShadeTimings& t = result.timings;
  std::cout << "phongcl shade: " << scene.source.string() << " + " << gbuffer.source.string() << "\n"
            << "  layout     " << loaded.layout << "\n"
            << (args.inputs.camera_space() ? "  space      camera (lights moved into the scene camera's frame)\n" : "")
            << "  image      " << gbuffer.width << " x " << gbuffer.height << ", " << with_commas(gbuffer.pixel_count())
            << " pixels: " << with_commas(result.counts.shaded) << " shaded, "
            << with_commas(gbuffer.pixel_count() - result.counts.shaded) << " background\n"
            << "  lights     " << result.point_lights - result.spot_lights << " point + "
            << (result.spot_lights > 0 ? std::to_string(result.spot_lights) + " spot + " : "")
            << result.directional_lights << " directional"
            << (result.area_lights > 0 ? " + " + std::to_string(result.area_lights) + " area" : "") << "\n"
            << "  device     " << describe(relighter.device()) << "\n"
            << "  kernel     " << result.kernel_summary << "\n"
            << "  build      " << to_string(result.cache) << ", " << milliseconds(t.build_ms)
            << (result.disk_cache_directory.empty() ? " (no disk cache: no writable cache directory)" : "") << "\n"
            << "  time       read " << milliseconds(read_ms) << ", pack " << milliseconds(t.pack_ms) << ", upload "
            << milliseconds(t.upload_ms) << ", kernel " << milliseconds(t.kernel_ms) << ", download "
            << milliseconds(t.download_ms) << ", write " << milliseconds(write_ms) << ", total "
            << milliseconds(milliseconds_since(start)) << " wall clock (shading "
            << mpixels_per_second(gbuffer.pixel_count(), t.total_ms) << "; kernel "
            << mpixels_per_second(gbuffer.pixel_count(), t.kernel_ms) << ")\n";
  if (result.culled) {
    const CullingStats& c = result.culling;
    std::cout << "  culling    light lists per " << c.tile_size << "x" << c.tile_rows << " tile, "
              << with_commas(c.shaded_tiles) << " with shaded pixels; lights per tile mean " << std::fixed
              << std::setprecision(1)
              << c.mean_lights_per_tile() << " (" << c.mean_holding_per_tile() << " holding all of it)"
              << std::defaultfloat << ", max "
              << c.max_lights_per_tile << "; " << milliseconds(c.culling_ms) << " (inside kernel time)\n";
  }
  if (!result.shadows.empty()) std::cout << "  shadows    " << result.shadows << "\n";
  if (!args.over.empty()) std::cout << "  over       " << composite.summary << "; " << milliseconds(composite_ms) << "\n";
  if (result.shadows_culled) {
    const ShadowCullingStats& c = result.shadow_culling;
    std::cout << "             " << with_commas(c.pairs) << " (tile, light) pairs: candidates per pair mean " << std::fixed
              << std::setprecision(2) << c.candidates_per_pair() << std::defaultfloat << ", "
              << with_commas(c.traversing) << " traversing the BVH; " << milliseconds(c.culling_ms)
              << " (inside kernel time)\n";
  }
  if (result.tiles > 1) std::cout << "  tiles      " << result.tiles << " (frame larger than one device allocation)\n";
  print_unshaded(result.counts);
  for (const auto& warning : loaded.warnings) std::cout << "  warning    " << warning << "\n";
  for (const auto& warning : result.warnings) std::cout << "  warning    " << warning << "\n";
  if (!result.disk_cache_problem.empty()) std::cout << "  note       " << result.disk_cache_problem << "\n";
  if (args.explain) {
    std::cout << "  recipe:\n";
    for (const auto& reason : result.recipe_reasons) std::cout << "    " << reason << "\n";
    std::cout << "  build options: " << result.build_options << "\n";
  }
  std::cout << "  wrote      " << written << " (" << exr::compression_name(outputs.compression) << ")\n";
}

}  // namespace

void add_shade_command(CLI::App& app) {
  auto args = std::make_shared<ShadeArguments>();
  CLI::App* command = app.add_subcommand("shade", "Shade a G-buffer with the OpenCL Phong kernel");
  args->inputs.add_options(*command);
  args->outputs.add_options(*command);
  args->outputs.add_aov_option(*command);
  command->add_option("--device", args->device, "OpenCL device: index or name (default: a GPU, else the CPU with most compute units; see phongcl devices)");
  command->add_option("--precision", args->precision, "double, precise (default), fast or half-storage")
      ->check(CLI::IsMember({"double", "precise", "fast", "half-storage"}));
  command->add_flag("--no-specialise", args->no_specialise, "Use the general kernel with everything compiled in");
  command->add_option("--lanes", args->lanes, "Pixels per work-item: 1, 2, 4, 8 or 16 (default: the device's preferred float width on CPUs, 1 on GPUs)");
  command->add_option("--culling", args->culling,
                      "Tiled light culling: auto (default: tiled from " + std::to_string(kAutoCullingLights) +
                          " point/spot lights with a range), tiled or none")
      ->check(CLI::IsMember({"auto", "tiled", "none"}));
  command->add_option("--tile", args->tile, "Culling tile size in pixels, 1 to 1024 (default 16)");
  command->add_option("--shadows", args->shadows,
                      "Shadows of the lights with \"shadows\": true: auto (default: geometry when the scene has "
                      "objects, else screen), screen (marched across the G-buffer), geometry (traced against the "
                      "scene's objects) or off")
      ->check(CLI::IsMember({"auto", "screen", "geometry", "off"}));
  command->add_option("--shadow-steps", args->shadow_steps,
                      "Screen-space shadows: samples along each ray (default " + std::to_string(args->shadow_steps) + ")")
      ->check(CLI::Range(1, 1024));
  command->add_option("--shadow-rays", args->shadow_rays,
                      "Geometry shadows: rays per pixel over an area light without its own \"shadow_rays\" (default " +
                          std::to_string(args->shadow_rays) + "; 1: one ray to the centre, a hard shadow)")
      ->check(CLI::Range(1, kMaxShadowRays));
  command->add_option("--environment-rays", args->environment_rays,
                      "Environment light: visibility rays per pixel where it has no \"rays\" of its own (default " +
                          std::to_string(args->environment_rays) + ")")
      ->check(CLI::Range(1, kMaxEnvironmentRays));
  command->add_option("--shadow-thickness", args->shadow_thickness,
                      "Screen-space shadows: how deep a surface is taken to be, in world units (0.25) or as a "
                      "percentage of its depth (default " + args->shadow_thickness + ")")
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              parse_shadow_thickness(text);
              return std::string();
            } catch (const std::invalid_argument& error) {
              return std::string(error.what());
            }
          },
          "LENGTH|PERCENT"));
  command->add_option("--over", args->over,
                      "A render with light-group passes (Blender's Combined_<group>) to relight: its Combined pass with "
                      "each light group the scene changed since \"rendered\" scaled (colour only) or re-shaded by "
                      "phongcl; the rest exactly as rendered (docs/compositing.md)");
  args->sequence.add_options(*command);
  command->add_flag("--explain", args->explain, "Print what was compiled in and out, and why, and the build options");
  command->callback([args] { run_shade(*args); });
}

}  // namespace phongcl::cli
