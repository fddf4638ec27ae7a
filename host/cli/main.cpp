// phongcl: deferred Phong shading of G-buffers with OpenCL. The lab's commands (reference, compare,
// bench, stability) live in phongcl-lab, which links the lab; phongcl hands them over to it.
#include "cli/commands.h"
#include "cli/lab_handover.h"
#include "cli/run_app.h"

int main(int argc, char** argv) {
  if (argc > 1 && phongcl::cli::is_lab_command(argv[1])) return phongcl::cli::hand_over_to_lab(argv);
  CLI::App app{"phongcl: deferred Phong shading of G-buffers with OpenCL", "phongcl"};
  app.footer(phongcl::cli::lab_commands_note());
  app.require_subcommand(1);
  phongcl::cli::add_gbuffer_command(app);
  phongcl::cli::add_shade_command(app);
  phongcl::cli::add_devices_command(app);
  phongcl::cli::add_serve_command(app);
  phongcl::cli::add_colors_command(app);
  phongcl::cli::add_png_command(app);
  return phongcl::cli::run_app(app, argc, argv);
}
