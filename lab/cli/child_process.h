#pragma once
// Runs a measured child process: its wall clock and peak resident memory (wait4's rusage), for the
// benchmarks that compare whole programs, including their start-up, against each other.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace phongcl::cli {

struct ChildRun {
  int exit_code = -1;  // -1: killed by a signal
  double seconds = 0.0;
  double peak_rss_mb = 0.0;
  std::string output;  // stdout (spawn) or what the body returned (fork)
};

// Runs argv[0] (looked up on PATH) with stdout captured and stderr appended to `error_log`.
ChildRun run_program(const std::vector<std::string>& argv, const std::filesystem::path& error_log);

// Runs body in a forked copy of this process and returns what it returned. Only for a parent that
// has started no threads that the child would need (no OpenEXR thread pool, no OpenCL): the child
// has only the calling thread.
ChildRun run_forked(const std::function<std::string()>& body);

}  // namespace phongcl::cli
