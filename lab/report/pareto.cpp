#include "report/pareto.h"

#include <cmath>

namespace phongcl {

std::vector<bool> pareto_front(const std::vector<CostPoint>& points) {
  auto finite = [](const CostPoint& p) { return std::isfinite(p.a) && std::isfinite(p.b); };
  auto dominates = [](const CostPoint& p, const CostPoint& q) {
    return p.a <= q.a && p.b <= q.b && (p.a < q.a || p.b < q.b);
  };
  std::vector<bool> front(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) continue;
    front[i] = true;
    for (std::size_t j = 0; j < points.size() && front[i]; ++j)
      if (j != i && finite(points[j]) && dominates(points[j], points[i])) front[i] = false;
  }
  return front;
}

}  // namespace phongcl
