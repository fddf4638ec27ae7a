#pragma once
// Summary statistics of repeated timings.
#include <vector>

namespace phongcl {

// Median (mean of the middle two for an even count) and minimum. Throw std::invalid_argument when empty.
double median(std::vector<double> values);
double minimum(const std::vector<double>& values);

}  // namespace phongcl
