#include "peers/many_lights.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace phongcl {

using std::numbers::pi;

namespace {

// The van der Corput radical inverse of i in base b: with bases 2, 3, 5 a Halton point set, even
// in space for any count (no clusters, no grid artefacts).
double radical_inverse(unsigned i, unsigned base) {
  double inverse = 1.0 / base, value = 0.0, digit = inverse;
  for (; i > 0; i /= base, digit *= inverse) value += (i % base) * digit;
  return value;
}

glm::dvec3 hue(double h) {
  const glm::dvec3 c(std::abs(h * 6.0 - 3.0) - 1.0, 2.0 - std::abs(h * 6.0 - 2.0), 2.0 - std::abs(h * 6.0 - 4.0));
  return glm::clamp(c, 0.0, 1.0) * 0.7 + 0.3;
}

bool reaches(const Light& light, const glm::dvec3& p) {
  if (light.type == LightType::directional) return false;
  const glm::dvec3 to_point = p - light.position;
  const double d = glm::length(to_point);
  if (light.has_range() && !(d < light.range)) return false;
  if (light.type != LightType::spot) return true;
  const double outer = (light.cone_angle_deg / 2.0 + light.penumbra_angle_deg) * pi / 180.0;
  return d > 0.0 && glm::dot(to_point / d, glm::normalize(light.direction)) > std::cos(outer);
}

std::vector<glm::dvec3> shaded_sample(const GBuffer& gbuffer, std::size_t step) {
  std::vector<glm::dvec3> points;
  for (std::size_t i = 0; i < gbuffer.pixel_count(); i += step)
    if (classify_pixel(gbuffer, i) == PixelClass::shaded)
      points.emplace_back(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]);
  return points;
}

double mean_reach(const std::vector<Light>& lights, const std::vector<glm::dvec3>& points) {
  double total = 0.0;
#pragma omp parallel for reduction(+ : total) schedule(static)
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const Light& light : lights) total += reaches(light, points[i]);
  return points.empty() ? 0.0 : total / static_cast<double>(points.size());
}

}  // namespace

double mean_lights_reaching(const Scene& scene, const GBuffer& gbuffer, std::size_t step) {
  return mean_reach(scene.lights, shaded_sample(gbuffer, std::max<std::size_t>(step, 1)));
}

double mean_lights_reaching_tiles(const Scene& scene, const GBuffer& gbuffer, int tile_size, int tile_rows) {
  const int tiles_x = (gbuffer.width + tile_size - 1) / tile_size;
  const int tiles_y = (gbuffer.height + tile_rows - 1) / tile_rows;
  double pairs = 0.0, shaded = 0.0;
#pragma omp parallel for reduction(+ : pairs, shaded) schedule(dynamic)
  for (int tile = 0; tile < tiles_x * tiles_y; ++tile) {
    std::vector<glm::dvec3> points;
    const int x0 = tile % tiles_x * tile_size, y0 = tile / tiles_x * tile_rows;
    for (int y = y0; y < std::min(y0 + tile_rows, gbuffer.height); ++y)
      for (int x = x0; x < std::min(x0 + tile_size, gbuffer.width); ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * gbuffer.width + x;
        if (classify_pixel(gbuffer, i) == PixelClass::shaded)
          points.emplace_back(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]);
      }
    if (points.empty()) continue;
    glm::dvec3 lo = points.front(), hi = points.front();
    for (const glm::dvec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    int reaching = 0;
    for (const Light& light : scene.lights) {
      // Beyond its range from the tile's box, a light reaches none of the tile's points.
      if (light.has_range() && glm::length(glm::max(glm::max(lo - light.position, light.position - hi), 0.0)) >= light.range)
        continue;
      reaching += std::any_of(points.begin(), points.end(), [&](const glm::dvec3& p) { return reaches(light, p); });
    }
    pairs += static_cast<double>(reaching) * static_cast<double>(points.size());
    shaded += static_cast<double>(points.size());
  }
  return shaded > 0.0 ? pairs / shaded : 0.0;
}

Scene with_many_lights(const Scene& scene, const GBuffer& gbuffer, int count, double target_reach) {
  if (count < 1) throw std::invalid_argument("light count must be >= 1, not " + std::to_string(count));
  // A sample of about 4,000 pixels: the bisection's means to about 2%.
  const std::vector<glm::dvec3> sample = shaded_sample(gbuffer, std::max<std::size_t>(gbuffer.pixel_count() / 4000, 1));
  if (sample.empty()) throw std::invalid_argument(gbuffer.source.string() + ": no shaded pixel to place lights around");
  glm::dvec3 lo = sample.front(), hi = sample.front();
  for (const glm::dvec3& p : sample) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 size = glm::max(hi - lo, glm::dvec3(1e-3 * glm::length(hi - lo)));
  lo.y += 0.05 * size.y;
  hi.y += 0.25 * size.y;

  Scene result = scene;
  result.lights.clear();
  for (int k = 0; k < count; ++k) {
    const auto i = static_cast<unsigned>(k + 1);
    Light light;
    light.type = k % 2 == 0 ? LightType::point : LightType::spot;
    light.position = lo + (hi - lo) * glm::dvec3(radical_inverse(i, 2), radical_inverse(i, 3), radical_inverse(i, 5));
    light.color = hue(radical_inverse(i, 7));
    light.falloff = Falloff::quadratic;
    if (light.type == LightType::spot) {
      const double tilt = 0.5 * radical_inverse(i, 11), turn = 2.0 * pi * radical_inverse(i, 13);
      light.direction = {tilt * std::cos(turn), -1.0, tilt * std::sin(turn)};
      light.cone_angle_deg = 60.0 + 60.0 * radical_inverse(i, 17);
      light.penumbra_angle_deg = 10.0;
    }
    result.lights.push_back(light);
  }
  // Mean reach grows with the range: bisect on a log scale between a tiny and the whole box.
  double low = 1e-4 * glm::length(size), high = 2.0 * glm::length(size);
  for (int step = 0; step < 30; ++step) {
    const double range = std::sqrt(low * high);
    for (Light& light : result.lights) light.range = range;
    (mean_reach(result.lights, sample) < target_reach ? low : high) = range;
  }
  const double range = std::sqrt(low * high);
  // Colours so that the typical pixel is lit about as brightly at any count: at range / 3 a light
  // gives its colour x (3 / range)^2, and about target_reach of them add up.
  const double brightness = range * range / 9.0 / target_reach * 2.0;
  for (Light& light : result.lights) {
    light.range = range;
    light.color *= brightness;
  }
  return result;
}

}  // namespace phongcl
