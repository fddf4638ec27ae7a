#pragma once
// The Pareto front of points where both coordinates are costs (smaller is better).
#include <vector>

namespace phongcl {

struct CostPoint {
  double a = 0.0, b = 0.0;  // e.g. run time and error
};

// front[i] is true when no other point is at least as good in both costs and strictly better in
// one. Equal points do not dominate each other, so both stay on the front. A point with a
// non-finite cost is never on the front and dominates nothing.
std::vector<bool> pareto_front(const std::vector<CostPoint>& points);

}  // namespace phongcl
