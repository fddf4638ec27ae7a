#include "cl/device.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "common/writable_directory.h"

namespace phongcl {

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// By name: no OpenCL query says "simulated". Oclgrind, Intel's FPGA emulator, and the like.
bool is_simulator(const DeviceInfo& info) {
  const std::string names = lower(info.platform + " " + info.name + " " + info.vendor);
  for (const char* word : {"oclgrind", "simulat", "emulat"})
    if (names.find(word) != std::string::npos) return true;
  return false;
}

DeviceInfo read_info(const cl::Platform& platform, const cl::Device& device, int index) {
  DeviceInfo info;
  info.index = index;
  info.platform = platform.getInfo<CL_PLATFORM_NAME>();
  info.platform_version = platform.getInfo<CL_PLATFORM_VERSION>();
  info.name = device.getInfo<CL_DEVICE_NAME>();
  info.vendor = device.getInfo<CL_DEVICE_VENDOR>();
  info.driver_version = device.getInfo<CL_DRIVER_VERSION>();
  info.device_version = device.getInfo<CL_DEVICE_VERSION>();
  info.is_cpu = (device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0;
  info.is_gpu = (device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) != 0;
  info.is_simulator = is_simulator(info);
  info.has_fp64 = device.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
  info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  info.global_memory = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  info.max_allocation = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  info.max_constant_buffer = device.getInfo<CL_DEVICE_MAX_CONSTANT_BUFFER_SIZE>();
  info.max_constant_args = device.getInfo<CL_DEVICE_MAX_CONSTANT_ARGS>();
  info.preferred_float_width = device.getInfo<CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT>();
  return info;
}

// PoCL keeps compiled kernels in $POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else ~/.cache/pocl, and
// when it cannot create that directory it reports zero devices without a word. Point it at a
// private temporary directory instead when the default is not usable (HOME unset or read-only).
void ensure_pocl_cache_dir() {
  if (std::getenv("POCL_CACHE_DIR")) return;
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  std::filesystem::path dir;
  if (xdg && *xdg) dir = std::filesystem::path(xdg) / "pocl";
  else if (home && *home) dir = std::filesystem::path(home) / ".cache" / "pocl";
  if (!dir.empty() && ensure_writable_directory(dir)) return;
  const auto fallback = std::filesystem::temp_directory_path() / ("phongcl-pocl-cache-" + std::to_string(::getuid()));
  if (ensure_writable_directory(fallback)) ::setenv("POCL_CACHE_DIR", fallback.c_str(), 0);
}

// PoCL's pthread workers float by default, and a worker woken for a launch is often placed on the
// core its sibling already runs on: at 0 lights one worker shaded the whole frame (2.5 ms of CPU
// against 0.1 ms, schedstat per thread) and 1 light took 3.7 to 23 ms. Pinned one per core
// (POCL_AFFINITY=1) both take half: 1.3 ms at 0 lights, median 5.0 ms at 1. A user's setting wins.
void pin_pocl_workers() { ::setenv("POCL_AFFINITY", "1", 0); }

}  // namespace

std::vector<Device> list_devices() {
  ensure_pocl_cache_dir();
  pin_pocl_workers();
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& error) {
    if (error.err() == -1001) return {};  // CL_PLATFORM_NOT_FOUND_KHR: no ICD installed
    throw;
  }
  std::vector<Device> devices;
  for (const auto& platform : platforms) {
    std::vector<cl::Device> found;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &found);
    } catch (const cl::Error& error) {
      if (error.err() == CL_DEVICE_NOT_FOUND) continue;
      throw;
    }
    for (const auto& device : found) {
      devices.push_back({device, read_info(platform, device, static_cast<int>(devices.size()))});
    }
  }
  return devices;
}

Device pick_device(const std::string& selector) {
  const auto devices = list_devices();
  if (devices.empty()) {
    throw std::runtime_error(
        "no OpenCL device found: install an OpenCL driver (e.g. Debian's pocl-opencl-icd); PoCL also "
        "reports none when it cannot create its kernel cache, so check that POCL_CACHE_DIR is writable");
  }
  if (selector.empty()) {
    std::vector<DeviceInfo> infos;
    for (const auto& device : devices) infos.push_back(device.info);
    const DefaultChoice choice = choose_default_device(infos);
    if (choice.index < 0)
      throw std::runtime_error("every OpenCL device here is a simulator or emulator (" + describe(infos.front()) +
                               "): choose one with --device, or install a real driver such as pocl-opencl-icd");
    return devices[static_cast<std::size_t>(choice.index)];
  }
  if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
    // More digits than any device count has is simply out of range (and would overflow stoul).
    if (selector.size() <= 6 && std::stoul(selector) < devices.size()) return devices[std::stoul(selector)];
    throw std::runtime_error("--device " + selector + ": there are only " + std::to_string(devices.size()) +
                             " OpenCL devices (see `phongcl devices`)");
  }
  for (const auto& device : devices) {
    if (lower(device.info.name).find(lower(selector)) != std::string::npos ||
        lower(device.info.platform).find(lower(selector)) != std::string::npos) {
      return device;
    }
  }
  throw std::runtime_error("--device " + selector + ": no OpenCL device matches (see `phongcl devices`)");
}

DefaultChoice choose_default_device(const std::vector<DeviceInfo>& devices) {
  // Rank: GPU, then CPU, then anything else; within a rank the most compute units; first listed on a tie.
  const auto rank = [](const DeviceInfo& d) { return d.is_gpu ? 2 : d.is_cpu ? 1 : 0; };
  DefaultChoice choice;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const DeviceInfo& d = devices[i];
    if (d.is_simulator) continue;
    if (choice.index >= 0) {
      const DeviceInfo& best = devices[static_cast<std::size_t>(choice.index)];
      if (rank(d) < rank(best) || (rank(d) == rank(best) && d.compute_units <= best.compute_units)) continue;
    }
    choice.index = static_cast<int>(i);
  }
  if (choice.index < 0) return {-1, "every device is a simulator or emulator: choose one with --device"};
  const DeviceInfo& chosen = devices[static_cast<std::size_t>(choice.index)];
  const std::string units = std::to_string(chosen.compute_units) + " compute units";
  choice.reason = chosen.is_gpu   ? "a GPU, the one with the most compute units (" + units + ")"
                  : chosen.is_cpu ? "no GPU; the CPU device with the most compute units (" + units + ")"
                                  : "no GPU or CPU device; the one with the most compute units (" + units + ")";
  return choice;
}

std::string describe(const DeviceInfo& info) {
  return info.name + " (" + info.platform + ", " + info.device_version + ", driver " + info.driver_version + ", " +
         (info.is_gpu ? "GPU" : info.is_cpu ? "CPU" : "other") + (info.is_simulator ? " simulator" : "") + ", " + std::to_string(info.compute_units) + " compute units)";
}

}  // namespace phongcl
