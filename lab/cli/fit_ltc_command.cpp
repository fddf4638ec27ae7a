// phongcl-lab fit-ltc: fits the LTC table of the Principled GGX lobe (lab/fit/ltc_fit.h) and writes
// it as the kernel header kernels/ltc_table.h.
#include <chrono>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/format.h"
#include "cli/lab_commands.h"
#include "fit/ltc_fit.h"

namespace phongcl::cli {

void add_fit_ltc_command(CLI::App& app) {
  auto* command = app.add_subcommand("fit-ltc", "Fit the LTC table of the Principled (v1) GGX lobe; write its kernel header");
  auto size = std::make_shared<int>(32);
  auto output = std::make_shared<std::string>("kernels/ltc_table.h");
  command->add_option("--size", *size, "entries per axis (roughness, view angle)")->check(CLI::Range(2, 256));
  command->add_option("-o,--output", *output, "the header to write");
  command->callback([size, output] {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<LtcEntry> table = fit_ltc_table(*size);
    write_ltc_header(table, *size, *output);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::cout << "phongcl fit-ltc: " << *size << " x " << *size << " entries in " << milliseconds(ms) << "\n"
              << "  wrote      " << *output << "\n";
  });
}

}  // namespace phongcl::cli
