#include "cli/run_app.h"

#include <iostream>
#include <new>

#include "cl/error_name.h"
#include "cl/opencl.h"

namespace phongcl::cli {

int run_app(CLI::App& app, int argc, char** argv) {
  const std::string name = app.get_name();
  try {
    app.parse(argc, argv);
    return 0;
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    // One line, like every other error; --help has the usage.
    std::cerr << name << ": " << error.what() << " (see --help)\n";
    return 2;
  } catch (const cl::BuildError& error) {
    std::cerr << name << ": kernel build failed: " << cl_error_name(error.err()) << "\n";
    for (const auto& [device, log] : error.getBuildLog()) {
      std::cerr << "build log for " << device.getInfo<CL_DEVICE_NAME>() << ":\n" << log << "\n";
    }
    return 1;
  } catch (const cl::Error& error) {
    std::cerr << name << ": OpenCL call " << error.what() << " failed: " << cl_error_name(error.err()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    // What the estimates before shading (shading/frame_memory.h) did not foresee: still one line.
    std::cerr << name << ": out of memory: this run needs more than the machine or the process's limit allows\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << name << ": " << error.what() << "\n";
    return 1;
  }
}

}  // namespace phongcl::cli
