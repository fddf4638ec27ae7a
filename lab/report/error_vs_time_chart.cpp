// error_vs_time.svg: max relative error (log) against median kernel time, the Pareto front drawn.
#include <filesystem>

#include "report/error_vs_time_report.h"

namespace phongcl {

namespace {

// A log axis cannot show zero: an exact variant is drawn here and says so in its label.
constexpr double kZeroErrorDrawnAt = 1e-17;

ChartPoint point_of(const VariantMeasurement& v) {
  ChartPoint p{v.kernel_median_ms, v.error.max_rel, v.label()};
  if (p.y <= 0) {
    p.y = kZeroErrorDrawnAt;
    p.label += " (error 0)";
  }
  if (v.error.nonfinite_mismatches > 0) p.label += " (non-finite pixels)";
  return p;
}

}  // namespace

Chart error_vs_time_chart(const ErrorVsTimeReport& report) {
  const std::vector<VariantMeasurement> variants = sorted_by_kernel_time(report.variants);
  const std::vector<bool> front = pareto_front(variants);

  Chart chart;
  chart.title = "Error against run time: " + std::filesystem::path(report.scene_file).parent_path().filename().string() +
                ", " + std::to_string(report.width) + " x " + std::to_string(report.height) + ", median of " +
                std::to_string(report.runs) + " runs";
  chart.x = {"median kernel time (ms, profiling events)", false};
  chart.y = {"max relative error vs double reference", true};
  ChartSeries specialised{"specialised (S)", {}, MarkerShape::circle, false, "#1f77b4"};
  ChartSeries general{"general (G)", {}, MarkerShape::square, false, "#d62728"};
  ChartSeries pareto{"Pareto front", {}, MarkerShape::none, true, "#555555"};
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const ChartPoint p = point_of(variants[i]);
    (variants[i].specialised ? specialised : general).points.push_back(p);
    if (front[i]) pareto.points.push_back({p.x, p.y, ""});  // in time order: the line runs left to right
  }
  // The front first, so its line lies under the markers.
  chart.series = {pareto, specialised, general};
  return chart;
}

}  // namespace phongcl
