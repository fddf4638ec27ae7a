// phongcl agreement: how often shaded light agrees with a renderer's, light by light (for shadows:
// Cycles' direct diffuse light of each light rendered alone; scripts/blender/shadow_scene.py), and
// with --median-at-most / --p99-at-most how closely (light types and groups: light_scene.py).
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include "cli/lab_commands.h"
#include "common/error.h"
#include "exr/exr_channels.h"
#include "report/light_agreement.h"

namespace phongcl::cli {

namespace {

struct AgreementArguments {
  std::vector<std::string> cycles, shaded, unshadowed;
  std::vector<std::string> cycles_unshadowed;  // the renderer's own unshadowed light, instead of --unshadowed
  std::string view_layer = "ViewLayer";
  std::string layer = "diffuse";  // phongcl's AOV layer: diffuse, or group.<name>
  std::string cycles_pass;        // empty: DiffDir x DiffCol; else a Cycles pass (Combined_<light group>)
  bool glossy = false;            // GlossDir x GlossCol instead, on pixels where it is >= 20% of the direct light
  bool per_object = false;        // with relative errors, each object index's too
  double tolerance = 0.05;
  double at_least = -1.0;  // percent; negative: report only
  double median_at_most = -1.0, p99_at_most = -1.0;  // relative errors; negative: report only
};

struct Planes {
  int width = 0, height = 0;
  std::vector<std::vector<float>> values;
};

Planes read_planes(const std::string& file, const std::vector<std::string>& channels) {
  exr::InputExr input(file);
  const PixelWindow window = input.data_window();
  Planes planes{window.width(), window.height(), {}};
  std::vector<exr::ReadSlice> slices;
  planes.values.resize(channels.size(), std::vector<float>(static_cast<std::size_t>(planes.width) * planes.height));
  for (std::size_t c = 0; c < channels.size(); ++c) slices.push_back({channels[c], planes.values[c].data(), 1});
  input.read(slices);
  return planes;
}

std::array<std::vector<float>, 3> rgb(Planes&& planes, std::size_t first) {
  return {std::move(planes.values[first]), std::move(planes.values[first + 1]), std::move(planes.values[first + 2])};
}

// Blender 3.x and 4.x name Cycles' passes in a multilayer EXR by their short names (DiffDir); 5.x by
// their full ones (Diffuse Direct). The pass prefix `layer + short + "."` or its 5.x form, whichever the
// file has.
std::string cycles_pass_prefix(const exr::InputExr& input, const std::string& layer, const std::string& short_name) {
  static const std::pair<const char*, const char*> kFullNames[] = {
      {"DiffDir", "Diffuse Direct"}, {"DiffCol", "Diffuse Color"}, {"GlossDir", "Glossy Direct"},
      {"GlossCol", "Glossy Color"},   {"IndexOB", "Object Index"}};
  for (const auto& [short_pass, full_pass] : kFullNames) {
    if (short_name != short_pass) continue;
    for (const std::string& name : input.channel_names())
      if (name.rfind(layer + full_pass + ".", 0) == 0) return layer + full_pass + ".";
  }
  return layer + short_name + ".";
}

// The renderer's light: DiffDir x DiffCol (GlossDir x GlossCol with `glossy`), or the named pass; then
// the object index and depth.
Planes read_cycles(const std::string& file, const std::string& layer, const std::string& pass, bool glossy = false) {
  const exr::InputExr input(file);
  const std::string dir = cycles_pass_prefix(input, layer, glossy ? "GlossDir" : "DiffDir"),
                    col = cycles_pass_prefix(input, layer, glossy ? "GlossCol" : "DiffCol");
  const std::vector<std::string> masks = {cycles_pass_prefix(input, layer, "IndexOB") + "X", layer + "Depth.Z"};
  if (pass.empty()) {
    Planes cycles = read_planes(file, {dir + "R", dir + "G", dir + "B", col + "R", col + "G", col + "B", masks[0], masks[1]});
    for (std::size_t i = 0; i < cycles.values[0].size(); ++i)
      for (int c = 0; c < 3; ++c) cycles.values[c][i] *= cycles.values[3 + c][i];
    cycles.values.erase(cycles.values.begin() + 3, cycles.values.begin() + 6);
    return cycles;
  }
  return read_planes(file, {layer + pass + ".R", layer + pass + ".G", layer + pass + ".B", masks[0], masks[1]});
}

// With --glossy: the pixels where the glossy light (summed over R, G, B) is at least 20% of the
// direct light, diffuse and glossy; below, a highlight's relative error is a dark pixel's.
void keep_glossy_pixels(std::vector<bool>& mask, const Planes& glossy, const Planes& diffuse) {
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const double g = glossy.values[0][i] + glossy.values[1][i] + glossy.values[2][i];
    const double d = diffuse.values[0][i] + diffuse.values[1][i] + diffuse.values[2][i];
    if (!(g > 0.0 && g >= 0.2 * (g + d))) mask[i] = false;
  }
}

void check_relative_errors(const AgreementArguments& args, const std::vector<LightImages>& lights,
                           const std::vector<bool>& mask) {
  bool within = true;
  for (std::size_t k = 0; k < lights.size(); ++k) {
    const RelativeErrors errors = relative_errors(lights[k], mask);
    std::printf("  light %zu    relative error median %.3g, 99th percentile %.3g over %zu lit pixels (%s)\n", k,
                errors.median, errors.p99, errors.pixels, args.shaded[k].c_str());
    within = within && errors.pixels > 0 && (args.median_at_most < 0.0 || errors.median <= args.median_at_most) &&
             (args.p99_at_most < 0.0 || errors.p99 <= args.p99_at_most);
  }
  if (!within)
    throw std::runtime_error("agreement: a light's relative error is beyond --median-at-most " +
                             std::to_string(args.median_at_most) + " or --p99-at-most " + std::to_string(args.p99_at_most) +
                             " (or it lights no pixel)");
}

// Each object index's median and 99th percentile relative error (each over its own pixels of `mask`)
// and its median ratio of shaded to expected light (R + G + B): where a median comes from, and which way.
void print_per_object(const LightImages& light, const std::vector<bool>& mask, const std::vector<float>& objects) {
  std::map<int, std::vector<bool>> masks;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      std::vector<bool>& own = masks[static_cast<int>(objects[i])];
      own.resize(mask.size(), false);
      own[i] = true;
    }
  for (const auto& [object, own] : masks) {
    const RelativeErrors errors = relative_errors(light, own);
    std::vector<double> ratios;
    for (std::size_t i = 0; i < own.size(); ++i) {
      const double expected = light.expected[0][i] + light.expected[1][i] + light.expected[2][i];
      if (own[i] && expected > 0.0) ratios.push_back((light.shaded[0][i] + light.shaded[1][i] + light.shaded[2][i]) / expected);
    }
    if (ratios.empty()) continue;
    std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2), ratios.end());
    std::printf("    object %d  relative error median %.3g, 99th percentile %.3g over %zu pixels; shaded / expected median %.3f\n",
                object, errors.median, errors.p99, errors.pixels, ratios[ratios.size() / 2]);
  }
}

void run_agreement(const AgreementArguments& args) {
  const bool relative = args.median_at_most >= 0.0 || args.p99_at_most >= 0.0;
  const std::size_t bases = args.unshadowed.size() + args.cycles_unshadowed.size();
  if (args.cycles.size() != args.shaded.size() || (!relative && args.cycles.size() != bases) ||
      (!args.unshadowed.empty() && !args.cycles_unshadowed.empty()))
    throw std::invalid_argument("agreement: give --cycles, --shaded and --unshadowed (or --cycles-unshadowed) once per"
                                " light, in the same order (neither with --median-at-most or --p99-at-most)");
  const std::string layer = args.view_layer.empty() ? "" : args.view_layer + ".";
  const std::string shaded_layer = args.layer.empty() ? "" : args.layer + ".";
  const std::vector<std::string> shaded_channels = {shaded_layer + "R", shaded_layer + "G", shaded_layer + "B"};
  std::vector<LightImages> lights;
  std::vector<bool> mask;
  std::vector<float> objects;  // the first render's object index
  int width = 0, height = 0;
  for (std::size_t k = 0; k < args.cycles.size(); ++k) {
    Planes cycles = read_cycles(args.cycles[k], layer, args.cycles_pass, args.glossy);
    if (k == 0) {
      width = cycles.width, height = cycles.height;
      mask = away_from_silhouettes(cycles.values[3], cycles.values[4], width, height);
      objects = cycles.values[3];
    }
    if (args.glossy) keep_glossy_pixels(mask, cycles, read_cycles(args.cycles[k], layer, ""));
    LightImages light;
    light.expected = rgb(std::move(cycles), 0);
    light.shaded = rgb(read_planes(args.shaded[k], shaded_channels), 0);
    if (relative)
      light.unshadowed = light.shaded;
    else if (!args.cycles_unshadowed.empty())
      light.unshadowed = rgb(read_cycles(args.cycles_unshadowed[k], layer, args.cycles_pass, args.glossy), 0);
    else
      light.unshadowed = rgb(read_planes(args.unshadowed[k], shaded_channels), 0);
    for (const auto* planes : {&light.expected, &light.shaded, &light.unshadowed})
      if ((*planes)[0].size() != mask.size()) throw InputError(args.shaded[k], "not the size of " + args.cycles[0]);
    lights.push_back(std::move(light));
  }
  if (relative) {
    std::printf("phongcl agreement: %zu lights, %dx%d, %s against %s\n", lights.size(), width, height, args.layer.c_str(),
                args.glossy ? "GlossDir x GlossCol (pixels where it is >= 20% of the direct light)"
                : args.cycles_pass.empty() ? "DiffDir x DiffCol" : args.cycles_pass.c_str());
    if (args.per_object)
      for (const LightImages& light : lights) print_per_object(light, mask, objects);
    check_relative_errors(args, lights, mask);
    return;
  }
  const LightAgreement agreement = light_agreement(lights, mask, width, args.tolerance);
  std::printf("phongcl agreement: %zu lights, %dx%d, tolerance %.3g of each light's unshadowed value (%s)\n",
              lights.size(), width, height, args.tolerance,
              args.cycles_unshadowed.empty() ? "phongcl's, --unshadowed" : "Cycles', --cycles-unshadowed");
  for (std::size_t k = 0; k < lights.size(); ++k)
    std::printf("  light %zu    %.2f%% of %zu pixels (%s)\n", k,
                100.0 * static_cast<double>(agreement.agreeing_per_light[k]) / std::max<double>(agreement.pixels, 1),
                agreement.pixels, args.cycles[k].c_str());
  std::printf("  every light %.2f%% of %zu pixels away from silhouettes; largest miss %.3g allowances at (%d, %d)\n",
              100.0 * agreement.fraction(), agreement.pixels, agreement.worst_miss, agreement.worst_x, agreement.worst_y);
  if (args.at_least >= 0.0 && 100.0 * agreement.fraction() < args.at_least)
    throw std::runtime_error("agreement: " + std::to_string(100.0 * agreement.fraction()) + "% is below --at-least " +
                             std::to_string(args.at_least) + "%");
}

}  // namespace

void add_agreement_command(CLI::App& app) {
  auto args = std::make_shared<AgreementArguments>();
  CLI::App* command = app.add_subcommand(
      "agreement", "How often shaded diffuse light agrees with Cycles' direct diffuse light, light by light");
  command->add_option("--cycles", args->cycles,
                      "Cycles render of one light alone: DiffDir, DiffCol (or --cycles-pass), IndexOB, Depth (per light)")
      ->required();
  command->add_option("--shaded", args->shaded, "phongcl --aov file of the same light (per light)")->required();
  command->add_option("--unshadowed", args->unshadowed,
                      "phongcl --aov file of the same light, shadows off (per light; not with --median-at-most)");
  command->add_option("--cycles-unshadowed", args->cycles_unshadowed,
                      "Cycles render of the same light with its shadows off, the tolerance's base instead of "
                      "--unshadowed (per light; shadow_scene.py --unshadowed)");
  command->add_option("--layer", args->layer, "The --aov files' layer to compare: diffuse (default) or group.<name>; '' the image's own R, G, B "
                      "(a shaded or composited --out)");
  command->add_option("--cycles-pass", args->cycles_pass,
                      "The Cycles pass to compare with (Combined_<light group>; default DiffDir x DiffCol)");
  command->add_flag("--glossy", args->glossy,
                    "Compare with GlossDir x GlossCol (use --layer specular) on the pixels where it is >= 20% of the "
                    "direct light");
  command->add_option("--median-at-most", args->median_at_most,
                      "Report each light's median and 99th percentile relative error; exit non-zero beyond this median");
  command->add_option("--p99-at-most", args->p99_at_most, "... or beyond this 99th percentile");
  command->add_flag("--per-object", args->per_object,
                    "With --median-at-most or --p99-at-most: each object index's errors and median shaded / expected too");
  command->add_option("--view-layer", args->view_layer, "The Cycles files' view layer (default ViewLayer)");
  command->add_option("--tolerance", args->tolerance, "Allowed miss, as a fraction of the light's unshadowed value (default 0.05)")
      ->check(CLI::Range(0.0, 1.0));
  command->add_option("--at-least", args->at_least, "Exit non-zero below this percentage of pixels");
  command->callback([args] { run_agreement(*args); });
}

}  // namespace phongcl::cli
