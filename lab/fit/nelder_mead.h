// Nelder and Mead's downhill simplex (1965) with the usual coefficients (reflect 1, expand 2,
// contract 1/2, shrink 1/2): the minimiser of the LTC fit, whose error has no cheap gradient.
#pragma once

#include <array>
#include <functional>

namespace phongcl {

using FitPoint = std::array<double, 4>;  // the LTC's a, c, b, d (ltc_fit.cpp)

// A local minimum of f near `start`, from a simplex of `step` along each axis; stops when the
// simplex's values differ by less than `tolerance` (relative) or after `iterations` steps.
FitPoint nelder_mead(const std::function<double(const FitPoint&)>& f, const FitPoint& start, double step,
                     int iterations, double tolerance);

}  // namespace phongcl
