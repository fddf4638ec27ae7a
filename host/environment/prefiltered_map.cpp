#include "environment/prefiltered_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <utility>
#include <vector>

#include "common/host_threads.h"

namespace phongcl {

using std::numbers::pi;

namespace {

// Below this fraction of the peak a cell's weight is left out: it makes a sharp lobe's convolution a
// few rows of the grid instead of all of it. What GGX's lobe holds beyond it is at most 0.1% (the
// half angle's tan^2 exceeds t with probability alpha^2 / (alpha^2 + t), and D falls to 1e-6 of its
// peak at t = 1000 alpha^2); Phong's tail is far less.
constexpr double kNegligibleWeight = 1e-6;

// The largest c at which lobe_weight is at most `fraction` of the peak, by bisection (the weight
// grows with c); -1 where it never falls that low over c > 0.
double cosine_where_weight_is(const SpecularLobe& lobe, double fraction) {
  const double target = fraction * lobe_weight(lobe, 1.0);
  if (lobe_weight(lobe, 1e-12) > target) return 0.0;
  double low = 0.0, high = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (low + high);
    (lobe_weight(lobe, middle) > target ? high : low) = middle;
  }
  return low;
}

// The grid's cells as directions with their solid angle and radiance, row by row.
struct Cells {
  int width = 0, height = 0;
  std::vector<glm::dvec3> directions;
  std::vector<double> solid_angles;  // per row
};

Cells cells_of(const RadianceGrid& radiance) {
  Cells cells{radiance.width, radiance.height, {}, {}};
  for (int y = 0; y < radiance.height; ++y) {
    cells.solid_angles.push_back(texel_solid_angle(y, radiance.width, radiance.height));
    for (int x = 0; x < radiance.width; ++x)
      cells.directions.push_back(equirect_direction((x + 0.5) / radiance.width, (y + 0.5) / radiance.height));
  }
  return cells;
}

// The weighted mean over the rows that can hold a direction within the lobe's support about r.
glm::dvec3 convolve(const RadianceGrid& radiance, const Cells& cells, const SpecularLobe& lobe, double support,
                    const glm::dvec3& r) {
  const double reach = std::acos(support) + pi / cells.height;  // a row's cells can be half a row nearer
  const double polar = std::acos(std::clamp(r.z, -1.0, 1.0));
  const int first = std::max(0, static_cast<int>(std::floor((polar - reach) / pi * cells.height)));
  const int last = std::min(cells.height - 1, static_cast<int>(std::ceil((polar + reach) / pi * cells.height)));
  glm::dvec3 sum(0.0);
  double weights = 0.0;
  for (int y = first; y <= last; ++y) {
    glm::dvec3 row_sum(0.0);
    double row_weights = 0.0;
    for (int x = 0; x < cells.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * cells.width + x;
      const double c = glm::dot(r, cells.directions[i]);
      if (c < support) continue;
      const double weight = lobe_weight(lobe, c);
      row_sum += weight * glm::dvec3(radiance.rgb[3 * i], radiance.rgb[3 * i + 1], radiance.rgb[3 * i + 2]);
      row_weights += weight;
    }
    sum += cells.solid_angles[static_cast<std::size_t>(y)] * row_sum;
    weights += cells.solid_angles[static_cast<std::size_t>(y)] * row_weights;
  }
  return weights > 0.0 ? sum / weights : glm::dvec3(0.0);
}

}  // namespace

double lobe_weight(const SpecularLobe& lobe, double c) {
  if (c <= 0.0) return 0.0;
  const double cosine = lobe.takes_cosine ? c : 1.0;
  if (lobe.kind == SpecularLobe::Kind::phong) return std::pow(c, lobe.parameter) * cosine;
  if (lobe.kind == SpecularLobe::Kind::blinn) return std::pow(0.5 * (1.0 + c), 0.5 * lobe.parameter) * cosine;
  // D(h) = alpha^2 / (pi (1 - (n.h)^2 (1 - alpha^2))^2), 1 - (n.h)^2 = (1 - c) / 2 kept apart from
  // the alpha^2 term: near the peak 1 - c would cancel.
  const double alpha_sq = std::max(lobe.parameter * lobe.parameter, 1e-7);
  const double root = 0.5 * (1.0 - c) + 0.5 * (1.0 + c) * alpha_sq;
  return alpha_sq / (pi * root * root) * c;
}

double lobe_integral(const SpecularLobe& lobe) {
  const double q = lobe.parameter;
  switch (lobe.kind) {
    case SpecularLobe::Kind::phong:
      return 2.0 / (q + (lobe.takes_cosine ? 2.0 : 1.0));
    case SpecularLobe::Kind::blinn: {
      // u = (1 + c) / 2 over [1/2, 1], a = q / 2: 4 integral u^a du, or with c = 2u - 1 the cosine's
      // 4 integral u^a (2u - 1) du.
      const double a = 0.5 * q;
      const auto moment = [](double power) { return (1.0 - std::pow(0.5, power)) / power; };  // integral u^(power-1)
      return lobe.takes_cosine ? 4.0 * (2.0 * moment(a + 2.0) - moment(a + 1.0)) : 4.0 * moment(a + 1.0);
    }
    case SpecularLobe::Kind::ggx:
      break;
  }
  return 1.0;  // GGX's integral, with its masking and Fresnel, is the split sum's table (kernels/environment_brdf.h)
}

double lobe_width(const SpecularLobe& lobe) {
  return std::acos(std::max(0.0, cosine_where_weight_is(lobe, std::exp(-0.5))));
}

int prefiltered_height(const SpecularLobe& lobe) {
  const double wanted = 2.0 * pi / lobe_width(lobe);
  int height = 4;
  while (height < wanted && height < kRadianceGridHeight) height *= 2;
  return height;
}

glm::dvec3 prefiltered_radiance(const RadianceGrid& radiance, const SpecularLobe& lobe, const glm::dvec3& r) {
  return convolve(radiance, cells_of(radiance), lobe, cosine_where_weight_is(lobe, kNegligibleWeight), r);
}

RadianceGrid prefilter(const RadianceGrid& radiance, const SpecularLobe& lobe) {
  if (radiance.width * radiance.height == 1) return radiance;
  const Cells cells = cells_of(radiance);
  const double support = cosine_where_weight_is(lobe, kNegligibleWeight);
  const int height = prefiltered_height(lobe), width = 2 * height;
  RadianceGrid map{width, height, std::vector<float>(3 * static_cast<std::size_t>(width) * height)};
  for_each_core_range(static_cast<std::size_t>(width) * height, 16, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
      const glm::dvec3 mean = convolve(radiance, cells, lobe, support, equirect_direction((x + 0.5) / width, (y + 0.5) / height));
      for (int c = 0; c < 3; ++c) map.rgb[3 * i + c] = static_cast<float>(mean[c]);
    }
  });
  return map;
}

std::shared_ptr<const RadianceGrid> prefiltered_of(const std::shared_ptr<const IrradianceMap>& map, const SpecularLobe& lobe) {
  if (map->radiance.width * map->radiance.height <= 1) return std::make_shared<const RadianceGrid>(map->radiance);
  // The map is held by its entry, so that its address names it while the entry lives.
  using Key = std::pair<const IrradianceMap*, SpecularLobe>;
  struct Entry {
    std::shared_ptr<const IrradianceMap> map;
    std::shared_ptr<const RadianceGrid> prefiltered;
  };
  static std::mutex mutex;
  static std::map<Key, Entry> cache;
  const Key key{map.get(), lobe};
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto found = cache.find(key); found != cache.end()) return found->second.prefiltered;
  }
  auto prefiltered = std::make_shared<const RadianceGrid>(prefilter(map->radiance, lobe));
  const std::lock_guard<std::mutex> lock(mutex);
  return cache.emplace(key, Entry{map, std::move(prefiltered)}).first->second.prefiltered;
}

}  // namespace phongcl
