// phongcl: deferred Phong shading of G-buffers with OpenCL. One top-level try: library code throws,
// only here is an error printed and an exit code chosen.
#include <iostream>

#include "cl/error_name.h"
#include "cl/opencl.h"
#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"phongcl: deferred Phong shading of G-buffers with OpenCL"};
  app.require_subcommand(1);
  phongcl::cli::add_gbuffer_command(app);
  phongcl::cli::add_shade_command(app);
  phongcl::cli::add_reference_command(app);
  phongcl::cli::add_compare_command(app);
  phongcl::cli::add_devices_command(app);
  phongcl::cli::add_bench_command(app);
  phongcl::cli::add_stability_command(app);
  phongcl::cli::add_serve_command(app);
  try {
    app.parse(argc, argv);
    return 0;
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    // One line, like every other error; --help has the usage.
    std::cerr << "phongcl: " << error.what() << " (see --help)\n";
    return 2;
  } catch (const cl::BuildError& error) {
    std::cerr << "phongcl: kernel build failed: " << phongcl::cl_error_name(error.err()) << "\n";
    for (const auto& [device, log] : error.getBuildLog()) {
      std::cerr << "build log for " << device.getInfo<CL_DEVICE_NAME>() << ":\n" << log << "\n";
    }
    return 1;
  } catch (const cl::Error& error) {
    std::cerr << "phongcl: OpenCL call " << error.what() << " failed: " << phongcl::cl_error_name(error.err()) << "\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "phongcl: " << error.what() << "\n";
    return 1;
  }
}
