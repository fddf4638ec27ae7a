#include "environment/equirect_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "common/error.h"
#include "exr/exr_channels.h"

namespace phongcl {

namespace {

const char* const kChannels[3] = {"R", "G", "B"};
// Rows read at a time: a multiple of every scanline compression's rows per chunk (1, 16, 32 and
// DWAB's 256), so that no chunk is decoded twice.
constexpr int kRowsPerBlock = 256;

// Where the map is larger than the grid: texel (x, y) goes to the cell holding its centre, weighted
// by its solid angle; the cells are divided by their summed weight at the end. Smaller: each cell
// takes the texel holding its centre.
class GridFolder {
 public:
  GridFolder(int width, int height)
      : width_(width), height_(height), grid_width_(std::max(1, std::min(width, kRadianceGridWidth))),
        grid_height_(std::max(1, std::min(height, kRadianceGridHeight))),
        sums_(3 * static_cast<std::size_t>(kRadianceGridWidth) * kRadianceGridHeight, 0.0),
        weights_(static_cast<std::size_t>(grid_width_) * grid_height_, 0.0) {
    for (int y = 0; y < height_; ++y) {
      const double weight = texel_solid_angle(y, width_, height_);
      for (int x = 0; x < width_; ++x) weights_[cell(x, y)] += weight;
    }
  }

  // Rows [first_row, first_row + rows) of one channel, `block` holding them from its start.
  void add_rows(const std::filesystem::path& name, int channel, const float* block, int first_row, int rows) {
    for (int y = first_row; y < first_row + rows; ++y) {
      const double weight = texel_solid_angle(y, width_, height_);
      for (int x = 0; x < width_; ++x) {
        const float value = block[static_cast<std::size_t>(y - first_row) * width_ + x];
        if (!std::isfinite(value) || value < 0.0f) {
          const std::string what = std::isnan(value) ? "NaN" : std::isinf(value) ? "inf" : "negative";
          throw InputError(name, "texel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                                     kChannels[channel] + " is " + what +
                                     ": an environment map holds finite radiances >= 0");
        }
        sums_[3 * cell(x, y) + channel] += weight * value;
      }
    }
  }

  RadianceGrid finish() const {
    RadianceGrid grid{kRadianceGridWidth, kRadianceGridHeight, {}};
    grid.rgb.resize(3 * static_cast<std::size_t>(grid.width) * grid.height);
    for (int y = 0; y < grid.height; ++y)
      for (int x = 0; x < grid.width; ++x) {
        // The folded cell holding this grid cell's centre: itself when the map was averaged down.
        const int fx = x * grid_width_ / grid.width, fy = y * grid_height_ / grid.height;
        const std::size_t folded = static_cast<std::size_t>(fy) * grid_width_ + fx;
        for (int c = 0; c < 3; ++c)
          grid.rgb[3 * (static_cast<std::size_t>(y) * grid.width + x) + c] =
              static_cast<float>(sums_[3 * folded + c] / weights_[folded]);
      }
    return grid;
  }

 private:
  std::size_t cell(int x, int y) const {
    return static_cast<std::size_t>(y * static_cast<std::int64_t>(grid_height_) / height_) * grid_width_ +
           static_cast<std::size_t>(x * static_cast<std::int64_t>(grid_width_) / width_);
  }

  int width_, height_, grid_width_, grid_height_;
  std::vector<double> sums_, weights_;
};

}  // namespace

double texel_solid_angle(int row, int width, int height) {
  using std::numbers::pi;
  const double top = pi * row / height, bottom = pi * (row + 1) / height;  // polar angles of the row's edges
  return 2.0 * pi / width * (std::cos(top) - std::cos(bottom));
}

RadianceGrid radiance_grid_from_planes(const std::filesystem::path& name, int width, int height,
                                       const std::vector<const float*>& planes) {
  GridFolder folder(width, height);
  for (int c = 0; c < 3; ++c) folder.add_rows(name, c, planes[static_cast<std::size_t>(c)], 0, height);
  return folder.finish();
}

RadianceGrid load_radiance_grid(const std::filesystem::path& file) {
  exr::InputExr exr(file);
  const PixelWindow window = exr.data_window();
  for (const char* channel : kChannels)
    if (!exr.has_channel(channel))
      throw InputError(file, std::string("has no channel ") + channel + ": an environment map needs R, G and B");
  const int width = window.width(), height = window.height();
  GridFolder folder(width, height);
  // A block of rows of the three channels at a time: 48 MiB for a 16384-wide map, whatever its height.
  const int block_rows = std::min(height, kRowsPerBlock);
  std::vector<float> block(3 * static_cast<std::size_t>(width) * block_rows);
  const std::size_t plane = static_cast<std::size_t>(width) * block_rows;
  for (int first = 0; first < height; first += block_rows) {
    const int rows = std::min(block_rows, height - first);
    exr.read_rows({exr::ReadSlice{kChannels[0], block.data(), 1}, exr::ReadSlice{kChannels[1], block.data() + plane, 1},
                   exr::ReadSlice{kChannels[2], block.data() + 2 * plane, 1}},
                  first, rows);
    for (int c = 0; c < 3; ++c) folder.add_rows(file, c, block.data() + c * plane, first, rows);
  }
  return folder.finish();
}

}  // namespace phongcl
