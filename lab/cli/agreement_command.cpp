// phongcl agreement: how often shaded light agrees with a renderer's, light by light (for shadows:
// Cycles' direct diffuse light of each light rendered alone; scripts/blender/shadow_scene.py).
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "cli/lab_commands.h"
#include "common/error.h"
#include "exr/exr_channels.h"
#include "report/light_agreement.h"

namespace phongcl::cli {

namespace {

struct AgreementArguments {
  std::vector<std::string> cycles, shaded, unshadowed;
  std::string view_layer = "ViewLayer";
  double tolerance = 0.05;
  double at_least = -1.0;  // percent; negative: report only
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

void run_agreement(const AgreementArguments& args) {
  if (args.cycles.size() != args.shaded.size() || args.cycles.size() != args.unshadowed.size())
    throw std::invalid_argument("agreement: give --cycles, --shaded and --unshadowed once per light, in the same order");
  const std::string layer = args.view_layer.empty() ? "" : args.view_layer + ".";
  std::vector<LightImages> lights;
  std::vector<bool> mask;
  int width = 0, height = 0;
  for (std::size_t k = 0; k < args.cycles.size(); ++k) {
    Planes cycles = read_planes(args.cycles[k], {layer + "DiffDir.R", layer + "DiffDir.G", layer + "DiffDir.B",
                                                 layer + "DiffCol.R", layer + "DiffCol.G", layer + "DiffCol.B",
                                                 layer + "IndexOB.X", layer + "Depth.Z"});
    if (k == 0) {
      width = cycles.width, height = cycles.height;
      mask = away_from_silhouettes(cycles.values[6], cycles.values[7], width, height);
    }
    for (std::size_t i = 0; i < mask.size(); ++i)
      for (int c = 0; c < 3; ++c) cycles.values[c][i] *= cycles.values[3 + c][i];  // DiffDir x DiffCol
    LightImages light;
    light.expected = rgb(std::move(cycles), 0);
    light.shaded = rgb(read_planes(args.shaded[k], {"diffuse.R", "diffuse.G", "diffuse.B"}), 0);
    light.unshadowed = rgb(read_planes(args.unshadowed[k], {"diffuse.R", "diffuse.G", "diffuse.B"}), 0);
    for (const auto* planes : {&light.shaded, &light.unshadowed})
      if ((*planes)[0].size() != mask.size())
        throw InputError(k < args.shaded.size() ? args.shaded[k] : "", "not the size of " + args.cycles[0]);
    lights.push_back(std::move(light));
  }
  const LightAgreement agreement = light_agreement(lights, mask, width, args.tolerance);
  std::printf("phongcl agreement: %zu lights, %dx%d, tolerance %.3g of each light's unshadowed value\n", lights.size(),
              width, height, args.tolerance);
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
  command->add_option("--cycles", args->cycles, "Cycles render of one light alone: DiffDir, DiffCol, IndexOB, Depth (per light)")
      ->required();
  command->add_option("--shaded", args->shaded, "phongcl --aov file of the same light (per light)")->required();
  command->add_option("--unshadowed", args->unshadowed, "phongcl --aov file of the same light, shadows off (per light)")
      ->required();
  command->add_option("--view-layer", args->view_layer, "The Cycles files' view layer (default ViewLayer)");
  command->add_option("--tolerance", args->tolerance, "Allowed miss, as a fraction of the light's unshadowed value (default 0.05)")
      ->check(CLI::Range(0.0, 1.0));
  command->add_option("--at-least", args->at_least, "Exit non-zero below this percentage of pixels");
  command->callback([args] { run_agreement(*args); });
}

}  // namespace phongcl::cli
