// phongcl devices: the OpenCL platforms and devices this machine has.
#include <iostream>

#include "cl/device.h"
#include "cli/commands.h"

namespace phongcl::cli {

namespace {

void run_devices() {
  const auto devices = list_devices();
  if (devices.empty()) throw std::runtime_error("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
  const Device chosen = pick_device("");
  for (const auto& device : devices) {
    const DeviceInfo& info = device.info;
    std::cout << (info.index == chosen.info.index ? "* " : "  ") << info.index << ": " << describe(info) << "\n"
              << "      fp64 " << (info.has_fp64 ? "yes" : "no") << ", global memory " << (info.global_memory >> 20)
              << " MiB, largest allocation " << (info.max_allocation >> 20) << " MiB, constant buffer "
              << (info.max_constant_buffer >> 10) << " KiB\n";
  }
  std::cout << "(* = the default device; choose another with --device INDEX or --device NAME)\n";
}

}  // namespace

void add_devices_command(CLI::App& app) {
  app.add_subcommand("devices", "List OpenCL platforms and devices")->callback(run_devices);
}

}  // namespace phongcl::cli
