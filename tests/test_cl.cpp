// The default OpenCL device: what a user wants when they name none.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cl/device.h"

namespace phongcl {
namespace {

DeviceInfo device(const std::string& platform, const std::string& name, bool cpu, bool gpu, unsigned units,
                  bool simulator = false) {
  DeviceInfo info;
  info.platform = platform;
  info.name = name;
  info.is_cpu = cpu;
  info.is_gpu = gpu;
  info.compute_units = units;
  info.is_simulator = simulator;
  return info;
}

const DeviceInfo kOclgrind = device("Oclgrind", "Oclgrind Simulator", true, false, 1, true);
const DeviceInfo kPocl = device("Portable Computing Language", "cpu-skylake", true, false, 2);

// Installing Oclgrind made it the default: it is listed first and calls itself a CPU.
TEST(DefaultDevice, NeverASimulatorListedFirst) {
  const DefaultChoice choice = choose_default_device({kOclgrind, kPocl});
  EXPECT_EQ(choice.index, 1);
  EXPECT_NE(choice.reason.find("no GPU; the CPU device with the most compute units (2"), std::string::npos)
      << choice.reason;
}

TEST(DefaultDevice, RealGpuFirstThenTheMostComputeUnits) {
  const DeviceInfo small_gpu = device("Vendor", "small", false, true, 8);
  const DeviceInfo big_gpu = device("Vendor", "big", false, true, 80);
  EXPECT_EQ(choose_default_device({kPocl, small_gpu, big_gpu, kOclgrind}).index, 2);
  EXPECT_EQ(choose_default_device({kPocl, small_gpu}).index, 1);
  const DeviceInfo big_cpu = device("Other CPU driver", "cpu", true, false, 64);
  EXPECT_EQ(choose_default_device({kPocl, big_cpu}).index, 1);
  EXPECT_EQ(choose_default_device({kPocl, kPocl}).index, 0);  // a tie keeps the first listed
}

TEST(DefaultDevice, OnlySimulatorsMeansNoDefault) {
  EXPECT_EQ(choose_default_device({kOclgrind}).index, -1);
  EXPECT_EQ(choose_default_device({}).index, -1);
}

}  // namespace
}  // namespace phongcl
