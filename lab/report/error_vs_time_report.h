#pragma once
// The error-against-run-time report of `phongcl bench` as plain data, and its three files:
// report.md (a table), report.json (the same data, for tools) and error_vs_time.svg (the chart).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "image/image.h"  // ErrorStats
#include "report/svg_chart.h"

namespace phongcl {

// One kernel variant. Times in milliseconds, each over the same timed runs after one untimed
// warm-up, kernel build excluded: kernel time from OpenCL profiling events; end to end the wall
// clock of pack + upload + kernel + download.
struct VariantMeasurement {
  std::string precision;  // "double", "precise", "fast", "half-storage"
  bool specialised = true;
  std::string build_options;
  std::vector<double> kernel_ms, end_to_end_ms;  // every timed run, in order
  double kernel_median_ms = 0.0, kernel_min_ms = 0.0, end_to_end_median_ms = 0.0;
  ErrorStats error;  // against the double-precision scalar reference, shaded pixels only

  std::string kernel_kind() const { return specialised ? "specialised" : "general"; }
  std::string label() const { return precision + (specialised ? " (S)" : " (G)"); }
  bool operator==(const VariantMeasurement&) const = default;
};

struct ErrorVsTimeReport {
  std::string scene_file, gbuffer_file, device;
  int width = 0, height = 0;
  std::size_t shaded_pixels = 0;
  int point_lights = 0, directional_lights = 0;
  int runs = 0;
  double relative_error_floor = 1e-6;  // relative error is |test - expected| / max(|expected|, floor)
  std::vector<std::string> notes;      // e.g. a variant the device cannot run
  std::vector<VariantMeasurement> variants;
  bool operator==(const ErrorVsTimeReport&) const = default;
};

// Every output lists variants in this order: by median kernel time, ties by label.
std::vector<VariantMeasurement> sorted_by_kernel_time(const std::vector<VariantMeasurement>& variants);
// On the front: no other variant has both a lower median kernel time and a lower max relative
// error. A variant with non-finite mismatches is never on it (its error is not bounded).
std::vector<bool> pareto_front(const std::vector<VariantMeasurement>& variants);

std::string render_markdown(const ErrorVsTimeReport& report);
nlohmann::json to_json(const ErrorVsTimeReport& report);
// Reads what to_json writes; throws nlohmann::json::exception on a missing field.
ErrorVsTimeReport error_vs_time_report_from_json(const nlohmann::json& json);
// Max relative error (log axis) against median kernel time, the Pareto front as a line.
Chart error_vs_time_chart(const ErrorVsTimeReport& report);

// Creates `directory` if needed and writes report.md, report.json and error_vs_time.svg into it,
// each atomically (see report/report_files.h for the errors).
void write_error_vs_time_report(const ErrorVsTimeReport& report, const std::filesystem::path& directory);

}  // namespace phongcl
