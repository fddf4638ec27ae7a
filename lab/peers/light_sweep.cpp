#include "peers/light_sweep.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/constants.hpp>

namespace phongcl {

namespace {

// Unit vector k of n on the upper hemisphere (z up in the frame's coordinates): heights evenly
// spaced, azimuths by the golden angle.
glm::dvec3 spiral_direction(int k, int n) {
  const double height = (k + 0.5) / n;
  const double azimuth = k * glm::pi<double>() * (3.0 - std::sqrt(5.0));
  const double ring = std::sqrt(1.0 - height * height);
  return {ring * std::cos(azimuth), ring * std::sin(azimuth), height};
}

glm::dvec3 hue(int k) {
  const double phase = 2.399963 * k;  // golden angle: neighbours differ
  return glm::dvec3(0.6 + 0.4 * std::cos(phase), 0.6 + 0.4 * std::cos(phase + 2.0944), 0.6 + 0.4 * std::cos(phase + 4.1888));
}

}  // namespace

Scene with_generated_lights(const Scene& scene, int count) {
  if (count < 0) throw std::invalid_argument("light count must be >= 0, got " + std::to_string(count));
  // A right-handed frame with z along the camera's up vector.
  const glm::dvec3 up = glm::normalize(scene.camera.up);
  const glm::dvec3 side = glm::normalize(glm::cross(std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), up));
  const glm::dvec3 forward = glm::cross(up, side);
  auto to_world = [&](const glm::dvec3& d) { return d.x * side + d.y * forward + d.z * up; };
  const double radius = 1.5 * std::max(glm::length(scene.camera.eye - scene.camera.look_at), 1e-3);

  Scene result = scene;
  result.lights.clear();
  const int points = (count + 1) / 2, directionals = count / 2;
  const double brightness = count > 0 ? 2.0 / count : 0.0;
  for (int k = 0; k < points; ++k) {
    result.lights.push_back({LightType::point, scene.camera.look_at + radius * to_world(spiral_direction(k, points)),
                             glm::dvec3(0.0), brightness * hue(k)});
  }
  for (int k = 0; k < directionals; ++k) {
    result.lights.push_back({LightType::directional, glm::dvec3(0.0), -to_world(spiral_direction(k, directionals)),
                             brightness * hue(points + k)});
  }
  return result;
}

namespace {

std::vector<int> rows_every(int height, int step) {
  if (step < 1) throw std::invalid_argument("row step must be >= 1, got " + std::to_string(step));
  std::vector<int> rows;
  for (int y = 0; y < height; y += step) rows.push_back(y);
  return rows;
}

void copy_rows(const Plane& source, Plane& target, int width, const std::vector<int>& rows) {
  if (source.empty()) return;
  target.resize(rows.size() * width);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::copy_n(source.begin() + static_cast<std::ptrdiff_t>(rows[r]) * width, width, target.begin() + r * width);
  }
}

}  // namespace

GBuffer every_nth_row(const GBuffer& gbuffer, int step) {
  const std::vector<int> rows = rows_every(gbuffer.height, step);
  GBuffer result;
  result.width = gbuffer.width;
  result.height = static_cast<int>(rows.size());
  result.data_window = result.display_window = PixelWindow{0, 0, result.width - 1, result.height - 1};
  result.source = gbuffer.source;
  for (int c = 0; c < 3; ++c) {
    copy_rows(gbuffer.position[c], result.position[c], gbuffer.width, rows);
    copy_rows(gbuffer.normal[c], result.normal[c], gbuffer.width, rows);
    copy_rows(gbuffer.ka[c], result.ka[c], gbuffer.width, rows);
    copy_rows(gbuffer.kd[c], result.kd[c], gbuffer.width, rows);
    copy_rows(gbuffer.ks[c], result.ks[c], gbuffer.width, rows);
  }
  copy_rows(gbuffer.material, result.material, gbuffer.width, rows);
  copy_rows(gbuffer.shininess, result.shininess, gbuffer.width, rows);
  return result;
}

Image every_nth_row(const Image& image, int step) {
  const std::vector<int> rows = rows_every(image.height, step);
  Image result(image.width, static_cast<int>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::copy_n(image.rgba.begin() + 4 * static_cast<std::ptrdiff_t>(rows[r]) * image.width, 4 * image.width,
                result.rgba.begin() + 4 * r * image.width);
  }
  return result;
}

GBuffer resample_nearest(const GBuffer& gbuffer, int width, int height) {
  if (width < 1 || height < 1) {
    throw std::invalid_argument("resample size must be at least 1x1, got " + std::to_string(width) + "x" + std::to_string(height));
  }
  GBuffer result;
  result.width = width;
  result.height = height;
  result.data_window = result.display_window = PixelWindow{0, 0, width - 1, height - 1};
  result.source = gbuffer.source;
  const std::size_t pixels = result.pixel_count();
  std::vector<std::size_t> from(pixels);
  for (int y = 0; y < height; ++y) {
    const auto sy = static_cast<std::size_t>((y + 0.5) * gbuffer.height / height);
    for (int x = 0; x < width; ++x) {
      const auto sx = static_cast<std::size_t>((x + 0.5) * gbuffer.width / width);
      from[static_cast<std::size_t>(y) * width + x] = sy * gbuffer.width + sx;
    }
  }
  auto resample = [&](const Plane& source, Plane& target) {
    if (source.empty()) return;  // an absent optional channel stays absent
    target.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) target[i] = source[from[i]];
  };
  for (int c = 0; c < 3; ++c) {
    resample(gbuffer.position[c], result.position[c]);
    resample(gbuffer.normal[c], result.normal[c]);
    resample(gbuffer.ka[c], result.ka[c]);
    resample(gbuffer.kd[c], result.kd[c]);
    resample(gbuffer.ks[c], result.ks[c]);
  }
  resample(gbuffer.material, result.material);
  resample(gbuffer.shininess, result.shininess);
  return result;
}

}  // namespace phongcl
