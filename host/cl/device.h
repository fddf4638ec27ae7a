#pragma once
// Finding OpenCL devices and describing them.
#include <string>
#include <vector>

#include "cl/device_info.h"
#include "cl/opencl.h"

namespace phongcl {

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

}  // namespace phongcl
