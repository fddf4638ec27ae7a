// RGBA images to and from EXR.
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "exr/exr_channels.h"
#include "image/image.h"

namespace phongcl {

namespace {

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};

}  // namespace

void write_exr(const Image& image, const std::filesystem::path& file, ExrPixelType type, ExrCompression compression) {
  write_layered_exr({{"", &image, true}}, file, type, compression);
}

void write_layered_exr(const std::vector<ExrLayer>& layers, const std::filesystem::path& file, ExrPixelType type,
                       ExrCompression compression) {
  if (layers.empty()) throw std::invalid_argument("write_layered_exr: no layers");
  const Image& first = *layers.front().image;
  const PixelWindow data_window = exr::data_window_for(first.data_window, first.width, first.height);
  std::vector<exr::WriteSlice> slices;
  for (const auto& layer : layers) {
    const Image& image = *layer.image;
    if (image.rgba.size() != 4 * image.pixel_count())
      throw std::invalid_argument("write_exr: image holds " + std::to_string(image.rgba.size()) +
                                  " floats, expected " + std::to_string(4 * image.pixel_count()));
    const PixelWindow window = exr::data_window_for(image.data_window, image.width, image.height);
    if (window.x_min != data_window.x_min || window.y_min != data_window.y_min || window.x_max != data_window.x_max ||
        window.y_max != data_window.y_max)
      throw std::invalid_argument("write_layered_exr: layer '" + layer.name + "' differs in size or window");
    for (int c = 0; c < (layer.with_alpha ? 4 : 3); ++c)
      slices.push_back({layer.name.empty() ? kChannelNames[c] : layer.name + "." + kChannelNames[c],
                        image.rgba.data() + c, 4});
  }
  exr::write_channels(file, data_window, exr::display_window_for(first.display_window, data_window), type, slices,
                    compression);
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
