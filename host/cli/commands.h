#pragma once
// Each phongcl subcommand registers itself on the app; its callback does the work and throws on
// failure (main() turns exceptions into a message and an exit code).
#include <CLI/CLI.hpp>

namespace phongcl::cli {

void add_gbuffer_command(CLI::App& app);
void add_shade_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_devices_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_stability_command(CLI::App& app);
void add_serve_command(CLI::App& app);

}  // namespace phongcl::cli
