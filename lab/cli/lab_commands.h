#pragma once
// The lab's subcommands, registered on phongcl-lab's app like the product's (cli/commands.h).
#include <CLI/CLI.hpp>

namespace phongcl::cli {

void add_reference_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_stability_command(CLI::App& app);
void add_agreement_command(CLI::App& app);
void add_fit_ltc_command(CLI::App& app);
void add_principled_tables_command(CLI::App& app);
void add_environment_brdf_command(CLI::App& app);

}  // namespace phongcl::cli
