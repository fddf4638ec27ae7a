// phongcl png: an EXR (linear, premultiplied) as an 8-bit PNG through an OCIO display, as shade's
// --png writes its previews: for a renderer's own frames, or an EXR written earlier.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/outputs.h"
#include "color/display.h"
#include "common/same_file.h"

namespace phongcl::cli {

namespace {

struct PngArguments {
  std::string input, output, ocio, blender, tone_map;
  DisplaySettings display;
  std::vector<double> background{0.0, 0.0, 0.0};
};

void run_png(const PngArguments& args) {
  refuse_shared_files({{"input", args.input, false, {}}, {"output", args.output, true, {}}});
  check_destination(args.output);
  const ColorConfig config = ColorConfig::load(args.ocio, args.blender);
  DisplaySettings settings = with_tone_map(args.display, args.tone_map);
  settings.background = {args.background[0], args.background[1], args.background[2]};
  const DisplayTransform display(config, settings);
  const Image image = read_exr(args.input);
  write_png(image, args.output, display);
  std::cout << "phongcl png: " << args.input << " -> " << args.output << " (" << image.width << " x " << image.height
            << ", " << display.display() << ", " << display.view() << (display.look().empty() ? "" : ", " + display.look())
            << (settings.exposure_stops != 0.0 ? ", exposure " + std::to_string(settings.exposure_stops) : "") << "; "
            << config.description() << ")\n";
}

}  // namespace

void add_png_command(CLI::App& app) {
  auto args = std::make_shared<PngArguments>();
  CLI::App* command = app.add_subcommand("png", "Write an EXR as an 8-bit PNG through an OCIO display and view");
  command->add_option("input", args->input, "EXR (R G B, and A if present; linear, premultiplied)")->required();
  command->add_option("output", args->output, "PNG to write (atomically)")->required();
  command->add_option("--ocio", args->ocio, "OpenColorIO config: a file, blender or builtin (default: $OCIO, else builtin)");
  command->add_option("--blender", args->blender, kBlenderOptionHelp);
  add_display_options(*command, args->display, args->tone_map);
  command->add_option("--background", args->background, "Working-space colour under transparent pixels: R G B (default 0 0 0)")
      ->expected(3);
  command->callback([args] { run_png(*args); });
}

}  // namespace phongcl::cli
