// RGBA images to and from EXR.
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "gbuffer/exr_channels.h"
#include "image/image.h"

namespace phongcl {

namespace {

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};

}  // namespace

void write_exr(const Image& image, const std::filesystem::path& file, ExrPixelType type) {
  const PixelWindow data_window = exr::data_window_for(image.data_window, image.width, image.height);
  if (image.rgba.size() != 4 * image.pixel_count())
    throw std::invalid_argument("write_exr: image holds " + std::to_string(image.rgba.size()) +
                                " floats, expected " + std::to_string(4 * image.pixel_count()));
  std::vector<exr::WriteSlice> slices;
  for (int c = 0; c < 4; ++c) slices.push_back({kChannelNames[c], image.rgba.data() + c, 4});
  exr::write_channels(file, data_window, exr::display_window_for(image.display_window, data_window), type,
                      slices);
}

Image read_exr(const std::filesystem::path& file) {
  exr::InputExr input(file);
  for (int c = 0; c < 3; ++c)
    if (!input.has_channel(kChannelNames[c]))
      throw InputError(file, std::string("missing channel ") + kChannelNames[c]);

  const PixelWindow data_window = input.data_window();
  Image image(data_window.width(), data_window.height());
  image.data_window = data_window;
  image.display_window = input.display_window();
  const bool has_alpha = input.has_channel("A");
  std::vector<exr::ReadSlice> slices;
  for (int c = 0; c < (has_alpha ? 4 : 3); ++c) slices.push_back({kChannelNames[c], image.rgba.data() + c, 4});
  if (!has_alpha)
    for (std::size_t i = 0; i < image.pixel_count(); ++i) image.pixel(i)[3] = 1.0f;  // opaque
  input.read(slices);
  return image;
}

}  // namespace phongcl
