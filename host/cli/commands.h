#pragma once
// Each phongcl subcommand registers itself on the app; its callback does the work and throws on
// failure (run_app() turns exceptions into a message and an exit code). The lab's commands: cli/lab_commands.h.
#include <CLI/CLI.hpp>

namespace phongcl::cli {

void add_gbuffer_command(CLI::App& app);
void add_shade_command(CLI::App& app);
void add_devices_command(CLI::App& app);
void add_serve_command(CLI::App& app);
void add_colors_command(CLI::App& app);
void add_png_command(CLI::App& app);

// --blender's help, the same wherever --ocio is.
inline constexpr const char* kBlenderOptionHelp =
    "The Blender executable whose OCIO config --ocio blender loads, e.g. a wrapper of scripts/setup.sh blender5 "
    "(default: $BLENDER, else an installed blender)";

}  // namespace phongcl::cli
