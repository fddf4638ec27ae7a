#include "composite/render_passes.h"

#include "common/error.h"
#include "common/joined.h"
#include "exr/exr_channels.h"

namespace phongcl {

namespace {

// The channel prefixes under which the file has a Combined pass: "ViewLayer." in Blender's
// multilayer EXRs (every version names Combined alike), "" in a file of that pass alone.
std::vector<std::string> combined_layers(const exr::InputExr& input) {
  std::vector<std::string> layers;
  const std::string suffix = "Combined.R";
  for (const std::string& name : input.channel_names())
    if (name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        (name.size() == suffix.size() || name[name.size() - suffix.size() - 1] == '.'))
      layers.push_back(name.substr(0, name.size() - suffix.size()));
  return layers;
}

Image blank_like(const exr::InputExr& input) {
  const PixelWindow window = input.data_window();
  Image image(window.width(), window.height());
  image.data_window = window;
  image.display_window = input.display_window();
  return image;
}

void read_pass(exr::InputExr& input, const std::string& prefix, bool alpha, Image& image) {
  std::vector<exr::ReadSlice> slices;
  for (int c = 0; c < (alpha ? 4 : 3); ++c) slices.push_back({prefix + "RGBA"[c], image.rgba.data() + c, 4});
  input.read(slices);
}

// The groups whose Combined_<group> pass is under `layer` ("ViewLayer.Combined_key.R" -> "key").
std::vector<std::string> group_pass_names(const exr::InputExr& input, const std::string& layer) {
  const std::string prefix = layer + "Combined_", suffix = ".R";
  std::vector<std::string> groups;
  for (const std::string& name : input.channel_names())
    if (name.size() > prefix.size() + suffix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      groups.push_back(name.substr(prefix.size(), name.size() - prefix.size() - suffix.size()));
  return groups;
}

}  // namespace

InputError missing_group_pass(const std::filesystem::path& render, const RenderPasses& passes, const std::string& group) {
  const std::string prefix = passes.layer + "Combined_" + group + ".";
  return InputError(render, "no pass for light group '" + group + "' (" + prefix + "R, G, B): render it with the group "
                            "in the view layer's Light Groups");
}

RenderPasses read_render_passes(const std::filesystem::path& file, const std::vector<std::string>& required) {
  exr::InputExr input(file);
  const std::vector<std::string> layers = combined_layers(input);
  if (layers.empty()) throw InputError(file, "no Combined pass (channels <layer>.Combined.R, G, B, A): not a render to composite over");
  if (layers.size() > 1)
    throw InputError(file, "a Combined pass in more than one view layer (" + joined(layers) + "): render one view layer");
  RenderPasses passes;
  passes.layer = layers.front();
  const std::string combined = passes.layer + "Combined.";
  if (!input.has_channel(combined + "A")) throw InputError(file, "its Combined pass has no alpha (" + combined + "A)");
  passes.combined = blank_like(input);
  read_pass(input, combined, true, passes.combined);
  for (const std::string& group : group_pass_names(input, passes.layer)) {
    Image pass = blank_like(input);
    read_pass(input, passes.layer + "Combined_" + group + ".", false, pass);
    passes.group_passes.emplace(group, std::move(pass));
  }
  for (const std::string& group : required)
    if (passes.group_passes.count(group) == 0) throw missing_group_pass(file, passes, group);
  return passes;
}

}  // namespace phongcl
