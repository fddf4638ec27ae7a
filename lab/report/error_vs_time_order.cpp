// The order and the Pareto front every output of the error-against-run-time report shares.
#include <algorithm>
#include <limits>

#include "report/error_vs_time_report.h"
#include "report/pareto.h"

namespace phongcl {

std::vector<VariantMeasurement> sorted_by_kernel_time(const std::vector<VariantMeasurement>& variants) {
  std::vector<VariantMeasurement> sorted = variants;
  std::stable_sort(sorted.begin(), sorted.end(), [](const VariantMeasurement& a, const VariantMeasurement& b) {
    if (a.kernel_median_ms != b.kernel_median_ms) return a.kernel_median_ms < b.kernel_median_ms;
    return a.label() < b.label();
  });
  return sorted;
}

std::vector<bool> pareto_front(const std::vector<VariantMeasurement>& variants) {
  std::vector<CostPoint> points;
  for (const auto& v : variants) {
    const bool bounded = v.error.nonfinite_mismatches == 0;
    points.push_back({v.kernel_median_ms, bounded ? v.error.max_rel : std::numeric_limits<double>::infinity()});
  }
  return pareto_front(points);
}

}  // namespace phongcl
