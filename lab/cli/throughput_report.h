#pragma once
// The throughput benchmark's results and their outputs: the Markdown table, the JSON other tools
// read (results_json: machine, then one object per row), and the report directory (report.md, chart).
#include <optional>
#include <string>
#include <vector>

#include "peers/machine_limits.h"

namespace phongcl::cli {

// Milliseconds over the timed runs (after one untimed warm-up).
struct RunStats {
  double median_ms = 0.0, min_ms = 0.0, max_ms = 0.0;
  int runs = 0;
};
RunStats summarize(std::vector<double> milliseconds);

struct ThroughputResult {
  std::string impl, variant;  // "opencl" | "cpp-scalar" | "cpp-simd" | "halide"; precision or "float"
  std::string not_run;        // "SKIP: why" (e.g. Halide not installed) or "FAILED: message"; no figures then
  std::string schedule;       // halide: the schedule that ran
  std::optional<double> compile_ms;  // halide: JIT compile, reported, not in the times
  int lights = 0, width = 0, height = 0;
  RunStats time;                        // opencl: kernel time from profiling events; peers: wall clock
  std::optional<RunStats> end_to_end;   // opencl: pack + upload + kernel + download, wall clock
  int timed_row_step = 1;               // > 1: timed on every n-th row, times scaled to the whole frame
  double bytes_per_pixel = 0.0, flops_per_pixel = 0.0;
  double mpix_per_s = 0.0, mpix_lights_per_s = 0.0;
  double roofline_mpix_per_s = 0.0, roofline_fraction = 0.0;
  std::optional<double> max_rel_err;    // against the double reference, over every error_row_step-th row
  int error_row_step = 1;
};

std::string markdown_table(const std::vector<ThroughputResult>& results);
// One line naming the Halide schedule(s) and JIT compile times; empty without halide figures.
std::string halide_note(const std::vector<ThroughputResult>& results);
// {"machine": {..., "load": ...}, "results": [...]}; end_to_end_median_ms for opencl only; max_rel_err null where not
// measured; a row that did not run has "not_run" (SKIP or FAILED and why) and null figures; halide rows add schedule and compile_ms.
std::string results_json(const MachineLimits& machine, const std::vector<ThroughputResult>& results, const std::string& load);
// report.md (machine, method, table), results.json and mpix_lights_vs_lights.svg in `directory`.
// `load`: the load average during the run, in words.
void write_throughput_report(const std::string& directory, const MachineLimits& machine, const std::string& device,
                             const std::string& inputs, const std::string& load, const std::vector<ThroughputResult>& results);

}  // namespace phongcl::cli
