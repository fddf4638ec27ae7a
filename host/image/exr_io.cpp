// RGBA images to and from EXR.
#include <ImfName.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "exr/exr_channels.h"
#include "image/image.h"

namespace phongcl {

namespace {

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};

bool has_color_where_transparent(const Image& image) {
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const float* p = image.pixel(i);
    if (p[3] == 0.0f && (p[0] != 0.0f || p[1] != 0.0f || p[2] != 0.0f)) return true;
  }
  return false;
}

// OpenEXR keeps the first 255 bytes of a channel name and silently drops the rest: a long layer's
// R, G and B would become one channel, two long names with one prefix one layer. Both are refused,
// naming the layer (its first bytes), before anything is written.
void check_channel_names(const std::vector<exr::WriteSlice>& slices, const std::vector<std::string>& layer_of) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < slices.size(); ++i) {
    const std::string& layer = layer_of[i];
    const std::string shown = layer.size() > 40 ? layer.substr(0, 40) + "..." : layer;
    if (slices[i].name.size() > static_cast<std::size_t>(Imf::Name::MAX_LENGTH))
      throw std::invalid_argument("write_layered_exr: layer '" + shown + "' (" + std::to_string(layer.size()) +
                                  " bytes) makes channel names longer than " + std::to_string(Imf::Name::MAX_LENGTH) +
                                  " bytes, OpenEXR's limit");
    if (!names.insert(slices[i].name).second)
      throw std::invalid_argument("write_layered_exr: channel '" + slices[i].name + "' twice (two layers named '" +
                                  shown + "')");
  }
}

Image without_color_where_transparent(const Image& image) {
  Image result = image;
  for (std::size_t i = 0; i < result.pixel_count(); ++i) {
    float* p = result.pixel(i);
    if (p[3] == 0.0f) p[0] = p[1] = p[2] = 0.0f;
  }
  return result;
}

// What one EXR of `layers` holds: its windows, and a slice per channel into the layers' images or into
// `cleared`, their copies with RGB 0 where alpha is 0 (the callers' images are const).
struct LayerChannels {
  PixelWindow data_window, display_window;
  std::vector<exr::WriteSlice> slices;
  std::vector<Image> cleared;
};

LayerChannels layer_channels(const std::vector<ExrLayer>& given, const ExrWriteOptions& options) {
  if (given.empty()) throw std::invalid_argument("write_layered_exr: no layers");
  std::vector<ExrLayer> layers = given;
  LayerChannels channels;
  channels.cleared.reserve(layers.size());  // the slices point into its images
  if (!options.keep_color_where_transparent)
    for (auto& layer : layers)
      if (layer.image->rgba.size() == 4 * layer.image->pixel_count() && has_color_where_transparent(*layer.image))
        layer.image = &channels.cleared.emplace_back(without_color_where_transparent(*layer.image));
  const Image& first = *layers.front().image;
  channels.data_window = exr::data_window_for(first.data_window, first.width, first.height);
  channels.display_window = exr::display_window_for(first.display_window, channels.data_window);
  std::vector<std::string> layer_of;  // each slice's layer, for check_channel_names' messages
  for (const auto& layer : layers) {
    const Image& image = *layer.image;
    if (image.rgba.size() != 4 * image.pixel_count())
      throw std::invalid_argument("write_exr: image holds " + std::to_string(image.rgba.size()) +
                                  " floats, expected " + std::to_string(4 * image.pixel_count()));
    const PixelWindow window = exr::data_window_for(image.data_window, image.width, image.height);
    const PixelWindow& data_window = channels.data_window;
    if (window.x_min != data_window.x_min || window.y_min != data_window.y_min || window.x_max != data_window.x_max ||
        window.y_max != data_window.y_max)
      throw std::invalid_argument("write_layered_exr: layer '" + layer.name + "' differs in size or window");
    for (int c = 0; c < (layer.with_alpha ? 4 : 3); ++c) {
      channels.slices.push_back({layer.name.empty() ? kChannelNames[c] : layer.name + "." + kChannelNames[c],
                                 image.rgba.data() + c, 4});
      layer_of.push_back(layer.name);
    }
  }
  check_channel_names(channels.slices, layer_of);
  return channels;
}

}  // namespace

void write_exr(const Image& image, const std::filesystem::path& file, const ExrWriteOptions& options) {
  write_layered_exr({{"", &image, true}}, file, options);
}

void write_layered_exr(const std::vector<ExrLayer>& layers, const std::filesystem::path& file,
                       const ExrWriteOptions& options) {
  const LayerChannels channels = layer_channels(layers, options);
  exr::write_channels(file, channels.data_window, channels.display_window, options.type, channels.slices,
                      options.compression, options.chromaticities);
}

std::string encode_exr(const Image& image, const ExrWriteOptions& options) {
  const LayerChannels channels = layer_channels({{"", &image, true}}, options);
  return exr::encode_channels(channels.data_window, channels.display_window, options.type, channels.slices,
                              options.compression, options.chromaticities);
}

Image read_exr(const std::filesystem::path& file, const std::string& layer) {
  exr::InputExr input(file);
  const std::string prefix = layer.empty() ? "" : layer + ".";
  for (int c = 0; c < 3; ++c)
    if (!input.has_channel(prefix + kChannelNames[c]))
      throw InputError(file, "missing channel " + prefix + kChannelNames[c]);

  const PixelWindow data_window = input.data_window();
  Image image(data_window.width(), data_window.height());
  image.data_window = data_window;
  image.display_window = input.display_window();
  const bool has_alpha = input.has_channel(prefix + "A");
  std::vector<exr::ReadSlice> slices;
  for (int c = 0; c < (has_alpha ? 4 : 3); ++c) slices.push_back({prefix + kChannelNames[c], image.rgba.data() + c, 4});
  if (!has_alpha)
    for (std::size_t i = 0; i < image.pixel_count(); ++i) image.pixel(i)[3] = 1.0f;  // opaque
  input.read(slices);
  return image;
}

}  // namespace phongcl
