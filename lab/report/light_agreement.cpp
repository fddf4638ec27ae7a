#include "report/light_agreement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace phongcl {

std::vector<bool> away_from_silhouettes(const std::vector<float>& object, const std::vector<float>& depth, int width,
                                        int height) {
  const auto index = [width](int x, int y) { return static_cast<std::size_t>(y) * width + x; };
  const auto sky = [&](std::size_t i) { return !(std::isfinite(depth[i]) && depth[i] < 1e9f); };
  std::vector<bool> mask(object.size(), false);
  for (int y = 1; y + 1 < height; ++y) {
    for (int x = 1; x + 1 < width; ++x) {
      bool inside = !sky(index(x, y));
      for (int dy = -1; dy <= 1 && inside; ++dy)
        for (int dx = -1; dx <= 1 && inside; ++dx)
          inside = !sky(index(x + dx, y + dy)) && object[index(x + dx, y + dy)] == object[index(x, y)];
      mask[index(x, y)] = inside;
    }
  }
  return mask;
}

RelativeErrors relative_errors(const LightImages& light, const std::vector<bool>& mask, double floor) {
  for (int c = 0; c < 3; ++c)
    if (light.expected[c].size() != mask.size() || light.shaded[c].size() != mask.size())
      throw std::invalid_argument("relative errors: every plane must have the mask's size");
  auto largest = [&](const std::array<std::vector<float>, 3>& planes, std::size_t i) {
    return std::max({static_cast<double>(planes[0][i]), static_cast<double>(planes[1][i]), static_cast<double>(planes[2][i])});
  };
  double brightest = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) brightest = std::max(brightest, largest(light.expected, i));
  std::vector<double> errors;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const double expected = largest(light.expected, i);
    if (!mask[i] || !(expected > floor * brightest)) continue;
    double miss = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double difference = std::abs(static_cast<double>(light.shaded[c][i]) - light.expected[c][i]);
      if (std::isnan(difference) || difference > miss) miss = difference;  // a NaN stays
    }
    errors.push_back(std::isfinite(miss) ? miss / expected : INFINITY);
  }
  RelativeErrors result;
  result.pixels = errors.size();
  if (errors.empty()) return result;
  std::sort(errors.begin(), errors.end());
  auto at = [&](double fraction) { return errors[static_cast<std::size_t>(fraction * static_cast<double>(errors.size() - 1))]; };
  result.median = at(0.5);
  result.p99 = at(0.99);
  return result;
}

LightAgreement light_agreement(const std::vector<LightImages>& lights, const std::vector<bool>& mask, int width,
                               double tolerance) {
  for (const LightImages& light : lights)
    for (int c = 0; c < 3; ++c)
      if (light.expected[c].size() != mask.size() || light.shaded[c].size() != mask.size() ||
          light.unshadowed[c].size() != mask.size())
        throw std::invalid_argument("light agreement: every plane must have the mask's size");
  LightAgreement result;
  result.agreeing_per_light.assign(lights.size(), 0);
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    ++result.pixels;
    bool all = true;
    for (std::size_t k = 0; k < lights.size(); ++k) {
      double miss = 0.0, unshadowed = 0.0;
      for (int c = 0; c < 3; ++c) {
        miss = std::max(miss, std::abs(static_cast<double>(lights[k].shaded[c][i]) - lights[k].expected[c][i]));
        unshadowed = std::max(unshadowed, static_cast<double>(lights[k].unshadowed[c][i]));
      }
      const double allowance = tolerance * unshadowed;
      const bool agrees = miss <= allowance;
      result.agreeing_per_light[k] += agrees;
      all = all && agrees;
      const double relative = allowance > 0.0 ? miss / allowance : (miss > 0.0 ? INFINITY : 0.0);
      if (relative > result.worst_miss) {
        result.worst_miss = relative;
        result.worst_x = static_cast<int>(i % static_cast<std::size_t>(width));
        result.worst_y = static_cast<int>(i / static_cast<std::size_t>(width));
      }
    }
    result.agreeing += all;
  }
  return result;
}

}  // namespace phongcl
