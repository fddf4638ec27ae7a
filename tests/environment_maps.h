#pragma once
// Environment maps made in code for the environment tests: an EXR from a function of the texel, and
// a sky (a gradient and a one-texel sun).
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "exr/exr_channels.h"

namespace phongcl::testing {

// An RGB float EXR of `width` x `height` from a function of the texel.
template <class Texel>
std::filesystem::path write_map(const std::filesystem::path& file, int width, int height, Texel texel) {
  std::vector<float> planes[3];
  for (auto& plane : planes) plane.resize(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 rgb = texel(x, y);
      for (int c = 0; c < 3; ++c) planes[c][static_cast<std::size_t>(y) * width + x] = static_cast<float>(rgb[c]);
    }
  const PixelWindow window{0, 0, width - 1, height - 1};
  exr::write_channels(file, window, window, ExrPixelType::float32,
                      {{"R", planes[0].data()}, {"G", planes[1].data()}, {"B", planes[2].data()}});
  return file;
}

// A sky: a gradient from a blue zenith to a dark ground.
inline glm::dvec3 gradient_texel(int y, int height) {
  const double up = 1.0 - (y + 0.5) / height;  // 1 at the top row
  return glm::dvec3(0.2, 0.3, 0.6) * up + glm::dvec3(0.05, 0.04, 0.03) * (1.0 - up);
}

// The gradient and a sun of one texel 2,000 times brighter (the stability case: a single bright
// texel carries most of the light).
inline glm::dvec3 sky_texel(int x, int y, int width, int height) {
  if (x == width / 3 && y == height / 4) return {2000.0, 1800.0, 1500.0};
  return gradient_texel(y, height);
}

}  // namespace phongcl::testing
