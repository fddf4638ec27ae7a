#pragma once
// An equirectangular float EXR as the environment light reads it (docs/environment.md): its R, G, B
// channels, validated, reduced to an integration grid of bounded size. The full-resolution map is
// never held: a block of rows at a time is read and folded into the grid.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace phongcl {

// The grid the irradiance is integrated over: a larger map is averaged down to it (each texel,
// weighted by its solid angle, into the cell holding its centre: the map's integral is kept); a
// smaller one is read as constant over each texel, every cell taking the texel holding its centre.
inline constexpr int kRadianceGridWidth = 256;
inline constexpr int kRadianceGridHeight = 128;

// Radiance in the map's frame, rows from the top (+Z) down, RGB interleaved.
struct RadianceGrid {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

// The solid angle of texel row `row` of an equirect map `width` x `height` (every texel of a row has the same).
double texel_solid_angle(int row, int width, int height);

// Reads `file`'s R, G and B channels (A and others ignored) into the grid. Throws InputError naming
// the file for a missing channel, and for an infinite, NaN or negative texel naming it: "texel (x, y)
// channel G is inf". Peak memory: 256 rows of the three channels as floats (48 MiB for a map 16384
// wide) plus the grid.
RadianceGrid load_radiance_grid(const std::filesystem::path& file);

// The same from channels in memory (planes of width x height floats, rows from the top), for maps
// made in code; `name` goes in the messages.
RadianceGrid radiance_grid_from_planes(const std::filesystem::path& name, int width, int height,
                                       const std::vector<const float*>& planes);

}  // namespace phongcl
