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

// `selector`: empty = the first CPU device (PoCL here), else the first device; a number = that
// index in list_devices(); otherwise the first device whose platform or device name contains it
// (case-insensitive). Throws std::runtime_error with advice when nothing matches.
Device pick_device(const std::string& selector);

}  // namespace phongcl
