#pragma once
// The passes of a render that a composite starts from: the Combined pass (RGBA, premultiplied, as
// renderers write it) and the Combined pass of each light group it has (Cycles' Combined_<group>,
// Blender 3.2 and newer), read as float from a multilayer EXR of Blender 3.x to 5.x.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "../common/error.h"
#include "../image/image.h"

namespace phongcl {

struct RenderPasses {
  Image combined;                             // RGBA, the file's data and display windows
  std::map<std::string, Image> group_passes;  // group name -> its Combined_<group> (alpha 0)
  std::string layer;                          // the view layer's channel prefix, e.g. "ViewLayer." ("" when none)
};

// Every light group's pass the file has. InputError naming the file when it has no Combined pass, more
// than one view layer with one (the composite would not know which), or no pass for a group in `required`.
RenderPasses read_render_passes(const std::filesystem::path& file, const std::vector<std::string>& required);

// InputError naming the render: `group` has no pass in it, and how to render one.
InputError missing_group_pass(const std::filesystem::path& render, const RenderPasses& passes, const std::string& group);

}  // namespace phongcl
