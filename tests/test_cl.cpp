// The default OpenCL device: what a user wants when they name none; work-group sizes; the program
// cache's bounds.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cl/compute_context.h"
#include "cl/device.h"
#include "cl/program_cache.h"
#include "cl/work_groups.h"
#include "opencl_required.h"
#include "temp_dir.h"

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

// On a CPU, many groups for the cores to share: the largest divisor up to the bound, 1 for a prime
// count; a GPU keeps its runtime's choice.
TEST(WorkGroups, ACpuGetsManySmallGroupsAGpuTheRuntimesChoice) {
  const auto local_size = [](const cl::NDRange& range) { return range.dimensions() == 0 ? 0 : range[0]; };
  EXPECT_EQ(local_size(spread_work_groups(kPocl, 129600, 64)), 64u);  // 1080p in rows of 16 lanes
  EXPECT_EQ(local_size(spread_work_groups(kPocl, 2040, 64)), 60u);
  EXPECT_EQ(local_size(spread_work_groups(kPocl, 2040, 1)), 1u);
  EXPECT_EQ(local_size(spread_work_groups(kPocl, 127, 64)), 1u);
  EXPECT_EQ(spread_work_groups(device("Vendor", "gpu", false, true, 80), 129600, 64).dimensions(), 0u);
  EXPECT_EQ(spread_work_groups(kPocl, 0, 64).dimensions(), 0u);
}

std::size_t files_in(const std::filesystem::path& directory) {
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) count += entry.path().extension() == ".clbin";
  return count;
}

// Each new light-count mix built and kept a new program, in memory and on disk, without end. The
// cache now keeps the ones used last: a program dropped from memory comes back from disk, and the
// disk keeps its newest files.
TEST(ProgramCache, BothCachesKeepTheProgramsUsedLast) {
  PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  testing::TempDir dir("program_cache");
  ProgramCache cache(dir.path, {2, 3, std::uintmax_t{1} << 30});
  const ComputeContext compute = make_compute_context(pick_device(""));
  const auto build = [&](const std::string& name) {
    return cache.build(compute, "kernel void " + name + "(global float* x) { x[0] = 1.0f; }", "").outcome;
  };
  for (const char* name : {"a", "b", "c"}) EXPECT_EQ(build(name), CacheOutcome::compiled) << name;
  EXPECT_EQ(cache.programs_in_memory(), 2u);
  EXPECT_EQ(files_in(dir.path), 3u);
  EXPECT_EQ(build("c"), CacheOutcome::memory_hit);
  EXPECT_EQ(build("a"), CacheOutcome::disk_hit) << "a left memory for b and c, and came back from disk";
  EXPECT_EQ(build("d"), CacheOutcome::compiled);
  EXPECT_EQ(files_in(dir.path), 3u);
  EXPECT_EQ(build("b"), CacheOutcome::compiled) << "b's file, the one used longest ago, made room for d's";
  EXPECT_EQ(cache.programs_in_memory(), 2u);
}

}  // namespace
}  // namespace phongcl
