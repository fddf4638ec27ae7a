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
  bool is_gpu = false;
  bool is_simulator = false;  // Oclgrind and other simulators or emulators: correct but very slow
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

// The device a user wants when they name none: a real GPU (the one with the most compute units),
// else the CPU device with the most compute units, else any other device; never a simulator or
// emulator (listing first and calling itself a CPU, Oclgrind took 17 s for a 320x240 frame).
struct DefaultChoice {
  int index = -1;      // into the list; -1 when every device is a simulator
  std::string reason;  // "a GPU with 80 compute units", for `phongcl devices`
};
DefaultChoice choose_default_device(const std::vector<DeviceInfo>& devices);

// `selector`: empty = choose_default_device(); a number = that index in list_devices(); otherwise
// the first device whose platform or device name contains it (case-insensitive). Throws
// std::runtime_error with advice when nothing matches.
Device pick_device(const std::string& selector);

// One line: "pthread-skylake-avx512 (Portable Computing Language, OpenCL 3.0 PoCL 3.1, CPU, 2 CUs)".
std::string describe(const DeviceInfo& info);

}  // namespace phongcl
