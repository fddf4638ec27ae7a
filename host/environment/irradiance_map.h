#pragma once
// The environment's diffuse light, precomputed (docs/environment.md): E(n) / pi over a small
// equirect grid of normals, each the exact convolution of the radiance grid with the clamped cosine
// (every cell with its solid angle). The kernel reads it bilinearly (kernels/environment.h).
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "environment/equirect_map.h"

namespace phongcl {

// Normals per row and rows of a map's irradiance: the cosine lobe leaves little above a few
// degrees' detail, and bilinear lookups between 64 x 32 centres (5.6 degrees apart) stay within
// the error docs/environment.md states.
inline constexpr int kIrradianceWidth = 64;
inline constexpr int kIrradianceHeight = 32;

// A bright cell taken out of the map (a sun): its direction in the map's frame and its radiance
// times its solid angle over pi, the E / pi it gives a normal facing it.
struct EnvironmentSunCell {
  glm::dvec3 direction{0.0, 0.0, 1.0};
  glm::dvec3 color{0.0};
};

// Up to this many cells are taken out (a sun of up to 8 x 8 grid cells, 11 degrees, as that many
// directions), each holding at least kSunShare of the map's power (luminance times solid angle) or
// kSunContrast times the map's mean radiance (a sun spread over many cells, none of them 1% of the
// power): E bends at their horizon faster than a bilinear lookup between the irradiance map's
// normals follows (a sun of 2,000 x the sky was 30% off there with it); as directional lights they
// cast the sun's shadow, penumbra included, one ray each; and left in the map they would make the
// visibility rays' estimate noisy (a 4-degree sun of 212 x the mean, in 33 cells: 91% of the pixels
// within 5% of Cycles at 64 rays, against 98% with 1,024).
inline constexpr int kMaxSunCells = 64;
inline constexpr double kSunShare = 0.01;
inline constexpr double kSunContrast = 20.0;

// E(n) / pi, rows from the top (+Z) down, RGB interleaved, in the map's frame, without the suns;
// E(n) / pi is the bilinear lookup plus each sun's color max(0, n.direction). `sky` is the radiance
// without the suns, averaged to the irradiance's size: what a blocked visibility ray takes away
// from E / pi (kernels/environment.h), so that a ray blocked by the dark ground below the horizon
// takes away little and one blocked towards the bright zenith much. `radiance` is the grid without
// the suns at its own size, which the specular maps are prefiltered from (prefiltered_map.h).
struct IrradianceMap {
  int width = 0, height = 0;
  std::vector<float> rgb;
  std::vector<EnvironmentSunCell> suns;
  RadianceGrid sky;
  RadianceGrid radiance;
};

// The unit direction of equirect coordinates (u, t) in [0, 1]^2, t from the top: Blender's mapping,
// u = 1/2 - atan2(y, x) / 2pi, the polar angle pi t.
glm::dvec3 equirect_direction(double u, double t);

// The convolution at kIrradianceWidth x kIrradianceHeight normals, every grid cell a direction at
// its centre weighted by its solid angle, once the suns are taken out.
IrradianceMap convolve_irradiance(const RadianceGrid& radiance);

// A uniform world of radiance `color`: E / pi = color for every normal, as one texel.
IrradianceMap uniform_irradiance(const glm::dvec3& color);

// The irradiance of an EXR map, computed once per file and modification time and kept for the
// process (a few maps of 24 KiB each). Throws what load_radiance_grid throws.
std::shared_ptr<const IrradianceMap> irradiance_of_file(const std::filesystem::path& file);

}  // namespace phongcl
