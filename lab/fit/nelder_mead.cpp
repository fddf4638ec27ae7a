#include "fit/nelder_mead.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace phongcl {

namespace {

FitPoint along(const FitPoint& from, const FitPoint& to, double t) {  // from + t (to - from)
  FitPoint p{};
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = from[k] + t * (to[k] - from[k]);
  return p;
}

}  // namespace

FitPoint nelder_mead(const std::function<double(const FitPoint&)>& f, const FitPoint& start, double step,
                     int iterations, double tolerance) {
  constexpr std::size_t n = std::tuple_size_v<FitPoint>;
  std::array<FitPoint, n + 1> simplex;
  std::array<double, n + 1> values{};
  for (std::size_t k = 0; k <= n; ++k) {
    simplex[k] = start;
    if (k > 0) simplex[k][k - 1] += step;
    values[k] = f(simplex[k]);
  }
  std::array<std::size_t, n + 1> order{};
  for (int iteration = 0; iteration < iterations; ++iteration) {
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    const std::size_t best = order[0], worst = order[n], second = order[n - 1];
    if (values[worst] - values[best] <= tolerance * std::abs(values[best])) break;
    FitPoint centroid{};
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t i = 0; i < n; ++i) centroid[i] += simplex[order[k]][i] / n;
    const FitPoint reflected = along(centroid, simplex[worst], -1.0);
    const double reflected_value = f(reflected);
    if (reflected_value < values[best]) {
      const FitPoint expanded = along(centroid, simplex[worst], -2.0);
      const double expanded_value = f(expanded);
      const bool expand = expanded_value < reflected_value;
      simplex[worst] = expand ? expanded : reflected;
      values[worst] = expand ? expanded_value : reflected_value;
      continue;
    }
    if (reflected_value < values[second]) {
      simplex[worst] = reflected;
      values[worst] = reflected_value;
      continue;
    }
    const bool outside = reflected_value < values[worst];
    const FitPoint contracted = along(centroid, outside ? reflected : simplex[worst], 0.5);
    const double contracted_value = f(contracted);
    if (contracted_value < std::min(reflected_value, values[worst])) {
      simplex[worst] = contracted;
      values[worst] = contracted_value;
      continue;
    }
    for (std::size_t k = 1; k <= n; ++k) {
      simplex[order[k]] = along(simplex[best], simplex[order[k]], 0.5);
      values[order[k]] = f(simplex[order[k]]);
    }
  }
  return simplex[std::min_element(values.begin(), values.end()) - values.begin()];
}

}  // namespace phongcl
