// phongcl-lab environment-brdf-table: writes kernels/environment_brdf.h, the split sum's BRDF table.
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "cli/lab_commands.h"
#include "reference/environment_brdf_table.h"

namespace phongcl::cli {

void add_environment_brdf_command(CLI::App& app) {
  auto output = std::make_shared<std::string>();
  CLI::App* command =
      app.add_subcommand("environment-brdf-table", "Write the environment's split-sum BRDF table (kernels/environment_brdf.h)");
  command->add_option("output", *output, "the header to write")->required();
  command->callback([output] {
    std::ofstream file(*output, std::ios::binary);
    file << environment_brdf_header(environment_brdf_table());
    if (!file.flush()) throw std::runtime_error(*output + ": cannot write");
    std::cout << "wrote " << *output << "\n";
  });
}

}  // namespace phongcl::cli
