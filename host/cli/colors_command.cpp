// phongcl colors: what an OpenColorIO config offers: displays and their views, looks, colour spaces,
// the working space and its primaries.
#include <iostream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "cli/commands.h"
#include "color/color_config.h"
#include "color/display.h"
#include "common/joined.h"

namespace phongcl::cli {

namespace {

std::string xy(const std::array<float, 2>& c) { return "(" + std::to_string(c[0]).substr(0, 6) + ", " + std::to_string(c[1]).substr(0, 6) + ")"; }

void run_colors(const std::string& which, const std::string& blender) {
  const ColorConfig config = ColorConfig::load(which, blender);
  std::cout << "phongcl colors: " << config.description() << "\n"
            << "  working    " << config.working_space() << " (scene_linear)";
  if (const auto c = config.working_chromaticities())
    std::cout << ", primaries R " << xy(c->red) << " G " << xy(c->green) << " B " << xy(c->blue) << ", white " << xy(c->white);
  std::cout << "\n";
  const std::string default_display = config.default_display();
  for (const std::string& display : config.displays()) {
    std::cout << "  display    " << display << (display == default_display ? " (default)" : "") << ": views "
              << joined(config.views(display)) << " (default " << config.default_view(display) << "); picker space "
              << config.picker_space(display) << "\n";
  }
  const std::vector<std::string> looks = config.looks();
  std::cout << "  looks      " << (looks.empty() ? "none" : joined(looks)) << "\n"
            << "  spaces     " << joined(config.color_spaces()) << "\n";
  for (const std::string& note : config.omitted()) std::cout << "  note       " << note << "\n";
  // How each view of the default display runs (color/view_pipeline.h): compiled, or OpenColorIO's
  // processor. A view that cannot be built is listed with its reason, the rest still are, and the
  // command fails after the listing.
  std::vector<std::string> broken;
  for (const std::string& view : config.views(default_display)) {
    DisplaySettings settings;
    settings.view = view;
    std::string pipeline;
    try {
      pipeline = DisplayTransform(config, settings).pipeline();
    } catch (const std::exception& error) {
      pipeline = std::string("cannot be built: ") + error.what();
      broken.push_back(view);
    }
    std::cout << "  pipeline   " << view << ": " << pipeline << "\n";
  }
  if (!broken.empty())
    throw std::runtime_error(config.description() + ": the views " + joined(broken) + " cannot be built (listed above)");
}

}  // namespace

void add_colors_command(CLI::App& app) {
  auto which = std::make_shared<std::string>();
  auto blender = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand("colors", "List an OpenColorIO config's displays, views, looks and colour spaces");
  command->add_option("--ocio", *which, "Config: a file, blender (an installed Blender's) or builtin (default: $OCIO, else builtin)");
  command->add_option("--blender", *blender, kBlenderOptionHelp);
  command->callback([which, blender] { run_colors(*which, *blender); });
}

}  // namespace phongcl::cli
