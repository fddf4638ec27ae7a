// phongcl bench: registers the benchmark's options and runs the error-against-run-time report.
#include <memory>

#include "cli/bench_arguments.h"
#include "cli/commands.h"

namespace phongcl::cli {

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArguments>();
  CLI::App* command = app.add_subcommand("bench", "Measure every kernel variant: error against run time");
  args->inputs.add_options(*command);
  command->add_option("--device", args->device, "OpenCL device: index or name (default: first CPU device)");
  command->add_option("--runs", args->runs, "Timed runs per measurement, after one warm-up (default 10)")
      ->check(CLI::PositiveNumber);
  command->add_option("--report", args->report_dir, "Directory for report.md, report.json and the chart");
  command->callback([args] { run_error_vs_time_bench(*args); });
}

}  // namespace phongcl::cli
