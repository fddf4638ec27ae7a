#pragma once
// Finding OpenCL devices and describing them.
#include <string>
#include <vector>

#include "cl/opencl.h"

namespace phongcl {

struct DeviceInfo {
  int index = 0;  // position in list_devices(), what --device N selects
  std::string platform, platform_version, name, vendor, driver_version, device_version;
  bool is_cpu = false;
  bool has_fp64 = false;
  unsigned compute_units = 0;
  unsigned long long global_memory = 0, max_allocation = 0, max_constant_buffer = 0;
  unsigned max_constant_args = 0;
  unsigned preferred_float_width = 1;  // floats per SIMD register the device prefers
};

struct Device {
  cl::Device handle;
  DeviceInfo info;
};

// Every device of every platform, numbered in order. Empty if there is no OpenCL platform.
std::vector<Device> list_devices();

// `selector`: empty = the first CPU device (PoCL here), else the first device; a number = that
// index in list_devices(); otherwise the first device whose platform or device name contains it
// (case-insensitive). Throws std::runtime_error with advice when nothing matches.
Device pick_device(const std::string& selector);

// One line: "pthread-skylake-avx512 (Portable Computing Language, OpenCL 3.0 PoCL 3.1, CPU, 2 CUs)".
std::string describe(const DeviceInfo& info);

}  // namespace phongcl
