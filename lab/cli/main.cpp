// phongcl-lab: what checks and measures phongcl (the double reference, image comparison, benchmarks,
// the stability catalogue). `phongcl <command>` runs these too, by handing over to this binary.
#include "cli/lab_commands.h"
#include "cli/run_app.h"

int main(int argc, char** argv) {
  CLI::App app{"phongcl-lab: the reference, comparisons, benchmarks, stability catalogue and fits of phongcl", "phongcl"};
  app.require_subcommand(1);
  phongcl::cli::add_reference_command(app);
  phongcl::cli::add_compare_command(app);
  phongcl::cli::add_bench_command(app);
  phongcl::cli::add_stability_command(app);
  phongcl::cli::add_agreement_command(app);
  phongcl::cli::add_fit_ltc_command(app);
  phongcl::cli::add_principled_tables_command(app);
  phongcl::cli::add_environment_brdf_command(app);
  return phongcl::cli::run_app(app, argc, argv);
}
