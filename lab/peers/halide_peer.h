#pragma once
// The Halide peer (lab/peers/halide_peer) runs as its own executable, `phongcl-halide-peer`, because
// Halide 14's LLVM and PoCL's cannot share a process; this is the host side that hands it the
// packed input and reads back its image and timings.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "peers/packed_frame.h"

namespace phongcl {

inline constexpr const char* kHalidePeerExecutable = "phongcl-halide-peer";

struct HalidePeerRun {
  std::string schedule, target;  // the Halide schedule that ran and the JIT target, e.g. x86-64-linux-avx512...
  double compile_ms = 0.0;       // JIT compile, not in times_ms
  int threads = 0;
  std::vector<double> times_ms;  // timed realize() calls, after one untimed warm-up
};

// The peer executable in `directory` (where the build puts it, next to `phongcl` and `phongcl-lab`), if it is there:
// it is built only when Halide is installed.
std::optional<std::filesystem::path> find_halide_peer(const std::filesystem::path& directory);

// Shades `frame` with the peer: one warm-up, then `runs` timed runs, fewer (at least min(3, runs))
// where they would exceed about `budget_ms`; writes 4 floats per pixel to `rgba`. Throws
// std::runtime_error with the peer's own message when it fails. Temporary files are removed.
HalidePeerRun run_halide_peer(const std::filesystem::path& executable, const PackedFrame& frame, const PackedScene& scene,
                              int runs, double budget_ms, float* rgba);

}  // namespace phongcl
