#pragma once
// The limits of this machine, measured in the same run as the benchmark they judge: the roofline
// bound of a shading run is min(bandwidth / bytes per pixel, FMA peak / flops per pixel).
#include <cstddef>
#include <string>

namespace phongcl {

struct MachineLimits {
  double bandwidth_gbs = 0.0;  // STREAM-style float triad, all cores
  double fma_gflops = 0.0;     // single precision, all cores, 2 flops per FMA lane
  int cores = 0;               // OpenMP threads used for both
  std::string cpu;             // /proc/cpuinfo "model name"
};

// Triad a[i] = b[i] + s * c[i] over three float arrays of `elements` each (choose 3 x 4 bytes x
// elements >> last-level cache), best of `repetitions`. Counted as STREAM counts it: 12 bytes per
// element (read b, read c, write a), not the 4 bytes more that write-allocate costs.
double measure_triad_bandwidth(std::size_t elements, int repetitions);

// Independent FMA chains in 512-bit registers on every core, best of `repetitions`.
double measure_fma_peak(int repetitions);

std::string cpu_model_name();
// /proc/loadavg's 1, 5 and 15 minute averages, "7.21 8.30 10.87": what else the machine was doing
// ("n/a" where there is no /proc/loadavg).
std::string load_average();

// Both measurements with sizes for this kind of machine (3 x 256 MB arrays; about a second in all).
MachineLimits measure_machine_limits();

}  // namespace phongcl
