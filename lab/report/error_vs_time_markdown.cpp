// report.md: a header saying what was measured and how, then one table row per variant.
#include <cmath>
#include <cstdio>

#include "report/error_vs_time_report.h"
#include "report/markdown_table.h"

namespace phongcl {

namespace {

std::string milliseconds(double ms) { return format_cell(ms < 10 ? "%.3f" : "%.2f", ms); }
std::string scientific(double value) { return format_cell("%.2e", value); }
std::string decibels(double db) { return std::isinf(db) ? "inf" : format_cell("%.1f", db); }

std::string worst_pixel(const ErrorStats& e) {
  char text[96];
  std::snprintf(text, sizeof text, "(%d, %d) %c: %.6g vs %.6g", e.worst_x, e.worst_y, "RGB"[e.worst_channel % 3],
                e.worst_test, e.worst_expected);
  return text;
}

// Kernel times are compared with the general precise kernel: everything compiled in, float.
const VariantMeasurement* baseline_of(const std::vector<VariantMeasurement>& variants) {
  for (const auto& v : variants)
    if (v.precision == "precise" && !v.specialised) return &v;
  return variants.empty() ? nullptr : &variants.front();
}

const VariantMeasurement* find(const std::vector<VariantMeasurement>& variants, const std::string& precision,
                               bool specialised) {
  for (const auto& v : variants)
    if (v.precision == precision && v.specialised == specialised) return &v;
  return nullptr;
}

}  // namespace

std::string render_markdown(const ErrorVsTimeReport& report) {
  const std::vector<VariantMeasurement> variants = sorted_by_kernel_time(report.variants);
  const std::vector<bool> front = pareto_front(variants);
  const VariantMeasurement* baseline = baseline_of(variants);

  std::string front_labels;
  for (std::size_t i = 0; i < variants.size(); ++i)
    if (front[i]) front_labels += (front_labels.empty() ? "" : ", ") + variants[i].label();

  std::string text = "# Error against run time\n\n";
  text += "- **Scene** `" + report.scene_file + "` with G-buffer `" + report.gbuffer_file + "`: " +
          std::to_string(report.width) + " x " + std::to_string(report.height) + ", " +
          std::to_string(report.shaded_pixels) + " shaded pixels; " + std::to_string(report.point_lights) +
          " point + " + std::to_string(report.directional_lights) + " directional lights\n";
  text += "- **Device** " + report.device + "\n";
  text += "- **Runs** " + std::to_string(report.runs) +
          " timed runs per variant after one untimed warm-up; **statistic**: median (and min) over those runs\n";
  text += "- **Kernel time**: OpenCL profiling events of the kernel launches only; the build is excluded "
          "(the program comes from the in-memory cache after the warm-up)\n";
  text += "- **End to end**: wall clock of pack + upload + kernel + download, build excluded\n";
  text += "- **Error**: against the double-precision scalar reference on every shaded pixel, channels R, G, B; "
          "relative error = |test - expected| / max(|expected|, " + format_cell("%g", report.relative_error_floor) +
          "); PSNR against the peak expected value\n";
  text += "- **Kernels**: (S) specialised to the scene (what it does not need compiled out), (G) general "
          "(everything compiled in)\n";
  text += "- **Pareto front** (no other variant both faster and more accurate): " +
          (front_labels.empty() ? std::string("none") : front_labels) + "\n";
  for (const auto& note : report.notes) text += "- **Note**: " + note + "\n";
  text += "\n";

  MarkdownTable table;
  table.headers = {"variant", "kernel", "median kernel (ms)", "min kernel (ms)", "median end to end (ms)",
                   "kernel time vs " + (baseline ? baseline->label() : std::string("-")), "max abs error",
                   "max rel error", "RMSE", "PSNR (dB)", "worst pixel (x, y) channel: got vs expected",
                   "non-finite mismatches", "Pareto front"};
  table.align = {ColumnAlign::left, ColumnAlign::left, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                 ColumnAlign::right, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                 ColumnAlign::left, ColumnAlign::right, ColumnAlign::left};
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const VariantMeasurement& v = variants[i];
    table.rows.push_back({v.precision, v.kernel_kind(), milliseconds(v.kernel_median_ms), milliseconds(v.kernel_min_ms),
                          milliseconds(v.end_to_end_median_ms),
                          format_cell("%.2fx", v.kernel_median_ms / baseline->kernel_median_ms),
                          scientific(v.error.max_abs), scientific(v.error.max_rel), scientific(v.error.rmse),
                          decibels(v.error.psnr_db), worst_pixel(v.error), std::to_string(v.error.nonfinite_mismatches),
                          front[i] ? "yes" : ""});
  }
  text += table.render();

  // What specialising buys, precision by precision.
  std::string speedups;
  for (const auto& v : variants) {
    if (!v.specialised) continue;
    const VariantMeasurement* general = find(variants, v.precision, false);
    if (!general) continue;
    speedups += "\n- " + v.precision + ": " + milliseconds(v.kernel_median_ms) + " ms specialised vs " +
                milliseconds(general->kernel_median_ms) + " ms general (" +
                format_cell("%.2fx", v.kernel_median_ms / general->kernel_median_ms) + ")";
  }
  if (!speedups.empty()) text += "\nSpecialised against general kernel, median kernel time:\n" + speedups + "\n";
  text += "\n![Max relative error against median kernel time](error_vs_time.svg)\n";
  return text;
}

}  // namespace phongcl
