#include "peers/machine_limits.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>

#include "peers/packed_frame.h"
#include "peers/simd_request.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// 16 floats: one AVX-512 register, written with GCC's vector extension so the FMAs are exactly what runs.
typedef float Lanes __attribute__((vector_size(64)));

// Enough independent chains to cover FMA latency (4 cycles) on two FMA ports, and fewer than the
// 32 vector registers so none spills.
constexpr int kChains = 16;
constexpr long kIterations = 20'000'000;

// Returns a value that depends on every chain, so the compiler cannot drop any of them.
float fma_chains(float seed) {
  Lanes acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = Lanes{} + seed * static_cast<float>(c + 1);
  const Lanes scale = Lanes{} + 0.999999f, add = Lanes{} + 1e-6f;  // stays bounded: converges to 1
  for (long it = 0; it < kIterations; ++it) {
    for (int c = 0; c < kChains; ++c) acc[c] = acc[c] * scale + add;
  }
  float sum = 0.0f;
  for (int c = 0; c < kChains; ++c) sum += acc[c][0] + acc[c][15];
  return sum;
}

}  // namespace

double measure_triad_bandwidth(std::size_t elements, int repetitions) {
  AlignedVector<float> a(elements), b(elements), c(elements);
  const auto n = static_cast<std::int64_t>(elements);
  // First touch on the threads that use the pages.
PHONGCL_PARALLEL_FOR_SIMD(schedule(static))
  for (std::int64_t i = 0; i < n; ++i) a[i] = 0.0f, b[i] = 1.0f, c[i] = 2.0f;
  double best = 1e300;
  const float s = 3.0f;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = Clock::now();
PHONGCL_PARALLEL_FOR_SIMD(schedule(static))
    for (std::int64_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    best = std::min(best, seconds_since(start));
  }
  if (a[elements / 2] != 7.0f) return 0.0;  // the loop ran (and was not optimised away)
  return 3.0 * sizeof(float) * static_cast<double>(elements) / best / 1e9;
}

double measure_fma_peak(int repetitions) {
  double best = 1e300;
  float sink = 0.0f;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = Clock::now();
#pragma omp parallel reduction(+ : sink)
    sink += fma_chains(static_cast<float>(omp_get_thread_num() + r));
    best = std::min(best, seconds_since(start));
  }
  const double flops = 2.0 * 16 * kChains * static_cast<double>(kIterations) * omp_get_max_threads();
  return sink == 0.0f ? 0.0 : flops / best / 1e9;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  if (!(in >> one >> five >> fifteen)) return "n/a";
  return one + " " + five + " " + fifteen;
}

std::string cpu_model_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(line.find_first_not_of(' ', colon + 1));
    }
  }
  return "unknown";
}

MachineLimits measure_machine_limits() {
  MachineLimits limits;
  limits.bandwidth_gbs = measure_triad_bandwidth(64u << 20, 5);
  limits.fma_gflops = measure_fma_peak(3);
  limits.cores = omp_get_max_threads();
  limits.cpu = cpu_model_name();
  return limits;
}

}  // namespace phongcl
