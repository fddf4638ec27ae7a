// Writing a G-buffer in the phongcl layout (used by the generator and by tests).
#include <stdexcept>
#include <string>
#include <vector>

#include "exr/exr_channels.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/gbuffer_layout.h"

namespace phongcl {

void write_gbuffer(const GBuffer& gbuffer, const std::filesystem::path& file, ExrPixelType type,
                   ExrCompression compression) {
  const PixelWindow data_window = exr::data_window_for(gbuffer.data_window, gbuffer.width, gbuffer.height);
  std::vector<exr::WriteSlice> slices;
  for (const auto& group : gbuffer_layout(gbuffer)) {
    if (!group.required && group.channels.front().plane->empty()) continue;  // group not in use
    for (const auto& channel : group.channels) {
      if (channel.plane->size() != gbuffer.pixel_count())
        throw std::invalid_argument("write_gbuffer: plane " + std::string(channel.name) + " has " +
                                    std::to_string(channel.plane->size()) + " values, expected " +
                                    std::to_string(gbuffer.pixel_count()));
      slices.push_back({channel.name, channel.plane->data()});
    }
  }
  exr::write_channels(file, data_window, exr::display_window_for(gbuffer.display_window, data_window),
                      type, slices, compression);
}

}  // namespace phongcl
