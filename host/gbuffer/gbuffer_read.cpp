// Reading a phongcl-layout G-buffer EXR into planes.
#include <string>
#include <vector>

#include "common/error.h"
#include "gbuffer/exr_channels.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/gbuffer_layout.h"

namespace phongcl {

namespace {

std::string join(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string joined = names.front();
  for (std::size_t i = 1; i < names.size(); ++i) joined += ", " + names[i];
  return joined;
}

template <class Group>
std::vector<std::string> missing_channels(const Group& group, const exr::InputExr& input) {
  std::vector<std::string> missing;
  for (const auto& channel : group.channels)
    if (!input.has_channel(channel.name)) missing.emplace_back(channel.name);
  return missing;
}

}  // namespace

GBuffer read_gbuffer(const std::filesystem::path& file) {
  exr::InputExr input(file);
  GBuffer g;
  g.source = file;
  g.data_window = input.data_window();
  g.display_window = input.display_window();
  g.width = g.data_window.width();
  g.height = g.data_window.height();

  // Every problem with the channel list is reported before any pixel is read.
  const auto layout = gbuffer_layout(g);
  std::vector<std::string> missing_required, missing_from_partial_group;
  for (const auto& group : layout) {
    const auto missing = missing_channels(group, input);
    auto& list = group.required ? missing_required : missing_from_partial_group;
    if (group.required || missing.size() < group.channels.size())
      list.insert(list.end(), missing.begin(), missing.end());
  }
  const std::string found = " (found: " + join(input.channel_names()) + ")";
  if (!missing_required.empty())
    throw InputError(file, (missing_required.size() == 1 ? "missing channel " : "missing channels ") +
                               join(missing_required) + found);
  if (!missing_from_partial_group.empty())
    throw InputError(file, "incomplete per-pixel material group, missing " +
                               join(missing_from_partial_group) + found);

  std::vector<exr::ReadSlice> slices;
  for (const auto& group : layout) {
    if (!missing_channels(group, input).empty()) continue;  // an absent optional group
    for (const auto& channel : group.channels) {
      channel.plane->resize(g.pixel_count());
      slices.push_back({channel.name, channel.plane->data()});
    }
  }
  input.read(slices);
  return g;
}

}  // namespace phongcl
