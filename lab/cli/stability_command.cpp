// phongcl stability: the stability catalogue and the accuracy bars on a device, as a table and,
// with --report, stability.md and stability.json.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cl/compute_context.h"
#include "cli/lab_commands.h"
#include "report/report_files.h"
#include "shading/phong_shader.h"
#include "stability/catalogue.h"
#include "stability/stability_report.h"

namespace phongcl::cli {

namespace {

struct StabilityArguments {
  std::string device;
  std::string report_directory;
};

void run_stability(const StabilityArguments& args) {
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  const StabilityRun run = run_catalogue(shader, stability_catalogue());
  const std::vector<BarFigure> bars = measure_accuracy_bars(shader);

  std::cout << "phongcl stability: " << run.cases.size() << " cases on " << run.device << "\n\n" << stability_table(run) << "\n";
  std::size_t failed_bars = 0;
  for (const BarFigure& bar : bars) {
    if (!bar.judged) continue;
    failed_bars += !bar.passed();
    std::cout << "bar  " << bar.bar << ", " << to_string(bar.precision) << ": max relative error " << bar.max_rel
              << (bar.passed() ? " (pass)" : " (FAIL)") << "\n";
  }
  if (!args.report_directory.empty()) {
    const std::filesystem::path directory(args.report_directory);
    std::filesystem::create_directories(directory);
    write_text_file(directory / "stability.md", stability_markdown(run, bars));
    write_text_file(directory / "stability.json", stability_json(run, bars));
    std::cout << "wrote " << (directory / "stability.md").string() << " and stability.json\n";
  }
  if (run.failures() > 0 || failed_bars > 0) {
    throw std::runtime_error("stability: " + std::to_string(run.failures()) + " of " + std::to_string(run.cases.size()) +
                             " cases and " + std::to_string(failed_bars) + " accuracy bars failed");
  }
}

}  // namespace

void add_stability_command(CLI::App& app) {
  auto args = std::make_shared<StabilityArguments>();
  CLI::App* command = app.add_subcommand("stability", "Run the numerical stability catalogue on a device");
  command->add_option("--device", args->device, "OpenCL device: index or name (default: a GPU, else the CPU with most compute units; see phongcl devices)");
  command->add_option("--report", args->report_directory, "Also write DIR/stability.md and DIR/stability.json");
  command->callback([args] { run_stability(*args); });
}

}  // namespace phongcl::cli
