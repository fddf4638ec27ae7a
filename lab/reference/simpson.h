#pragma once

// Simpson's rule, the references' quadrature for smooth one-dimensional integrands.

namespace phongcl {

// The integral of f over [low, high] by Simpson's rule with `intervals` (even) intervals; f returns a
// double or a glm vector.
template <typename F>
auto simpson(F f, double low, double high, int intervals) {
  const double h = (high - low) / intervals;
  auto sum = f(low) + f(high);
  for (int k = 1; k < intervals; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(low + k * h);
  return sum * (h / 3.0);
}

}  // namespace phongcl
