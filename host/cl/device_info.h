#pragma once
// What phongcl knows about an OpenCL device, without OpenCL's headers (the public API shows it).
#include <string>

namespace phongcl {

struct DeviceInfo {
  int index = 0;  // position in list_devices(), what --device N selects
  std::string platform, platform_version, name, vendor, driver_version, device_version;
  bool is_cpu = false;
  bool is_gpu = false;
  bool is_simulator = false;  // Oclgrind and other simulators or emulators: correct but very slow
  bool has_fp64 = false;
  unsigned compute_units = 0;
  unsigned long long global_memory = 0, max_allocation = 0, max_constant_buffer = 0;
  unsigned max_constant_args = 0;
  unsigned preferred_float_width = 1;  // floats per SIMD register the device prefers
};

// One line: "pthread-skylake-avx512 (Portable Computing Language, OpenCL 3.0 PoCL 3.1, CPU, 2 CUs)".
std::string describe(const DeviceInfo& info);

}  // namespace phongcl
