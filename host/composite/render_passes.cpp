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

}  // namespace

RenderPasses read_render_passes(const std::filesystem::path& file, const std::vector<std::string>& groups) {
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
  for (const std::string& group : groups) {
    const std::string prefix = passes.layer + "Combined_" + group + ".";
    if (!input.has_channel(prefix + "R"))
      throw InputError(file, "no pass for light group '" + group + "' (" + prefix + "R, G, B): render it with the group "
                             "in the view layer's Light Groups");
    Image pass = blank_like(input);
    read_pass(input, prefix, false, pass);
    passes.group_passes.emplace(group, std::move(pass));
  }
  return passes;
}

}  // namespace phongcl
