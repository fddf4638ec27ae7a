// phongcl-lab principled-tables: writes kernels/principled_tables.h, the tables Cycles' Principled BSDF
// v2 reads, by integrating GGX (lab/fit/ggx_tables.h).
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>

#include "fit/ggx_tables.h"
#include "cli/format.h"
#include "cli/lab_commands.h"
#include "common/error.h"

namespace phongcl::cli {

namespace {

struct TablesArguments {
  std::string out = "kernels/principled_tables.h";
  int grid = 256;
};

void run_principled_tables(const TablesArguments& args) {
  const auto start = std::chrono::steady_clock::now();
  const std::string text = principled_tables_source(compute_principled_tables(args.grid), args.grid);
  std::ofstream file(args.out, std::ios::binary);
  if (!(file << text)) throw InputError(args.out + ": cannot write the tables");
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::cout << "phongcl principled-tables: " << args.grid << " x " << args.grid << " visible normals per integral, "
            << milliseconds(ms) << "\n  wrote      " << args.out << "\n";
}

}  // namespace

void add_principled_tables_command(CLI::App& app) {
  auto args = std::make_shared<TablesArguments>();
  CLI::App* command = app.add_subcommand("principled-tables", "Integrate the GGX tables of the Principled BSDF v2");
  command->add_option("--out", args->out, "the header to write")->capture_default_str();
  command->add_option("--grid", args->grid, "visible normals per integral: grid x grid")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  command->callback([args] { run_principled_tables(*args); });
}

}  // namespace phongcl::cli
