#pragma once
// Wall-clock time of a benchmark's step, on the monotonic clock.
#include <chrono>

namespace phongcl {

// Milliseconds from `start` to now.
inline double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace phongcl
