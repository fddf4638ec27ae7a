#include "environment/irradiance_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <utility>

#include "common/error.h"
#include "common/host_threads.h"

namespace phongcl {

using std::numbers::pi;

namespace {

// Rec. 709 luminance: the power the suns are chosen by.
double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

}  // namespace

glm::dvec3 equirect_direction(double u, double t) {
  const double azimuth = pi * (1.0 - 2.0 * u), polar = pi * t;
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)};
}

namespace {

// Each cell's direction times its solid angle, once: the convolution's inner loop is then a dot product.
struct Cell {
  glm::dvec3 weighted_direction;
  glm::dvec3 radiance;
};

// The cells holding kSunShare of the power or kSunContrast times the mean radiance, brightest first,
// at most kMaxSunCells, taken out of `cells` (their radiance set to 0).
std::vector<EnvironmentSunCell> take_out_suns(std::vector<Cell>& cells) {
  double total = 0.0, solid_angles = 0.0;
  for (const Cell& cell : cells) {
    total += luminance(cell.radiance) * glm::length(cell.weighted_direction);
    solid_angles += glm::length(cell.weighted_direction);
  }
  std::vector<std::size_t> order(cells.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto power = [&](std::size_t i) { return luminance(cells[i].radiance) * glm::length(cells[i].weighted_direction); };
  const auto is_sun = [&](std::size_t i) {
    return power(i) >= kSunShare * total || luminance(cells[i].radiance) >= kSunContrast * total / solid_angles;
  };
  const std::size_t considered = std::min<std::size_t>(kMaxSunCells, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(considered), order.end(),
                    [&](std::size_t a, std::size_t b) { return power(a) > power(b); });
  std::vector<EnvironmentSunCell> suns;
  for (std::size_t k = 0; k < considered && total > 0.0 && is_sun(order[k]); ++k) {
    Cell& cell = cells[order[k]];
    const double solid_angle = glm::length(cell.weighted_direction);
    suns.push_back({cell.weighted_direction / solid_angle, cell.radiance * (solid_angle / pi)});
    cell.radiance = glm::dvec3(0.0);
  }
  return suns;
}

// The cells' radiance (a grid of `width` x `height`) averaged down to `out_width` x `out_height`,
// each cell weighted by its solid angle into the coarse cell holding its centre.
RadianceGrid average_cells(const std::vector<Cell>& cells, int width, int height, int out_width, int out_height) {
  std::vector<glm::dvec3> sums(static_cast<std::size_t>(out_width) * out_height, glm::dvec3(0.0));
  std::vector<double> weights(sums.size(), 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Cell& cell = cells[static_cast<std::size_t>(y) * width + x];
      const double solid_angle = glm::length(cell.weighted_direction);
      const std::size_t coarse = static_cast<std::size_t>(y * out_height / height) * out_width + x * out_width / width;
      sums[coarse] += cell.radiance * solid_angle;
      weights[coarse] += solid_angle;
    }
  RadianceGrid grid{out_width, out_height, std::vector<float>(3 * sums.size(), 0.0f)};
  for (std::size_t i = 0; i < sums.size(); ++i)
    if (weights[i] > 0.0)
      for (int c = 0; c < 3; ++c) grid.rgb[3 * i + c] = static_cast<float>(sums[i][c] / weights[i]);
  return grid;
}

}  // namespace

IrradianceMap convolve_irradiance(const RadianceGrid& radiance) {
  std::vector<Cell> cells;
  cells.reserve(static_cast<std::size_t>(radiance.width) * radiance.height);
  for (int y = 0; y < radiance.height; ++y) {
    const double solid_angle = texel_solid_angle(y, radiance.width, radiance.height);
    for (int x = 0; x < radiance.width; ++x) {
      const float* rgb = &radiance.rgb[3 * (static_cast<std::size_t>(y) * radiance.width + x)];
      const glm::dvec3 direction = equirect_direction((x + 0.5) / radiance.width, (y + 0.5) / radiance.height);
      cells.push_back({direction * solid_angle, glm::dvec3(rgb[0], rgb[1], rgb[2])});
    }
  }
  IrradianceMap map{kIrradianceWidth, kIrradianceHeight, {}, take_out_suns(cells), {}, {}};
  map.sky = average_cells(cells, radiance.width, radiance.height, map.width, map.height);
  map.radiance = average_cells(cells, radiance.width, radiance.height, radiance.width, radiance.height);
  map.rgb.resize(3 * static_cast<std::size_t>(map.width) * map.height);
  for_each_core_range(static_cast<std::size_t>(map.width) * map.height, 64,
                      [&](std::size_t, std::size_t begin, std::size_t end) {
                        for (std::size_t i = begin; i < end; ++i) {
                          const int x = static_cast<int>(i % map.width), y = static_cast<int>(i / map.width);
                          const glm::dvec3 n = equirect_direction((x + 0.5) / map.width, (y + 0.5) / map.height);
                          glm::dvec3 sum(0.0);
                          for (const Cell& cell : cells) sum += std::max(0.0, glm::dot(n, cell.weighted_direction)) * cell.radiance;
                          for (int c = 0; c < 3; ++c) map.rgb[3 * i + c] = static_cast<float>(sum[c] / pi);
                        }
                      });
  return map;
}

IrradianceMap uniform_irradiance(const glm::dvec3& color) {
  const std::vector<float> rgb{static_cast<float>(color.x), static_cast<float>(color.y), static_cast<float>(color.z)};
  return {1, 1, rgb, {}, {1, 1, rgb}, {1, 1, rgb}};
}

std::shared_ptr<const IrradianceMap> irradiance_of_file(const std::filesystem::path& file) {
  std::error_code error;
  const auto modified = std::filesystem::last_write_time(file, error);
  if (error) throw InputError(file, "cannot open (" + error.message() + ")");
  using Key = std::pair<std::filesystem::path, std::filesystem::file_time_type>;
  static std::mutex mutex;
  static std::map<Key, std::shared_ptr<const IrradianceMap>> cache;
  const Key key{std::filesystem::absolute(file), modified};
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto found = cache.find(key); found != cache.end()) return found->second;
  }
  auto map = std::make_shared<const IrradianceMap>(convolve_irradiance(load_radiance_grid(file)));
  const std::lock_guard<std::mutex> lock(mutex);
  return cache.emplace(key, std::move(map)).first->second;
}

}  // namespace phongcl
