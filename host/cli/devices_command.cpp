// phongcl devices: the OpenCL platforms and devices this machine has.
#include <iostream>
#include <vector>

#include "cl/device.h"
#include "cli/commands.h"

namespace phongcl::cli {

namespace {

void run_devices() {
  const auto devices = list_devices();
  if (devices.empty()) throw std::runtime_error("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
  std::vector<DeviceInfo> infos;
  for (const auto& device : devices) infos.push_back(device.info);
  const DefaultChoice chosen = choose_default_device(infos);
  for (const auto& device : devices) {
    const DeviceInfo& info = device.info;
    std::cout << (info.index == chosen.index ? "* " : "  ") << info.index << ": " << describe(info) << "\n"
              << "      fp64 " << (info.has_fp64 ? "yes" : "no") << ", global memory " << (info.global_memory >> 20)
              << " MiB, largest allocation " << (info.max_allocation >> 20) << " MiB, constant buffer "
              << (info.max_constant_buffer >> 10) << " KiB\n";
  }
  std::cout << "(* = the default device: " << chosen.reason;
  for (const auto& info : infos)
    if (info.is_simulator) std::cout << "; " << info.index << " is a simulator, used only when named";
  std::cout << ". Choose another with --device INDEX or --device NAME)\n";
}

}  // namespace

void add_devices_command(CLI::App& app) {
  app.add_subcommand("devices", "List OpenCL platforms and devices")->callback(run_devices);
}

}  // namespace phongcl::cli
