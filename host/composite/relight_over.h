#pragma once
// The frame relit over a render, end to end: which groups the edited scene changed, the render's passes
// of those, phongcl's terms of each changed group alone (as rendered and as edited), the composite.
// What `phongcl shade --over` runs; a library user calls it with a Relighter that holds the frame.
#include <filesystem>
#include <string>
#include <vector>

#include <phongcl/relighter.hpp>

#include "composite/composite.h"
#include "composite/group_edits.h"

namespace phongcl {

struct RelitOver {
  Composite composite;           // the image, and the fit of each changed group
  std::vector<GroupEdit> edits;  // per light group: unchanged, scaled or re-shaded
  std::string view_layer;        // the render's view layer ("" when its passes have none)
};

// `relighter`: the G-buffer of the render, with RelighterOptions::terms on (std::logic_error
// otherwise); it keeps the lights it had. `edited`: the scene with its "rendered" lights (a
// Relighter's scene() after set_lights keeps those it was made with). InputError naming the render or the scene for what a composite cannot use
// (composite/group_edits.h, composite/render_passes.h), or a render of another size than the G-buffer.
RelitOver relight_over(Relighter& relighter, const std::filesystem::path& render, const Scene& edited);

}  // namespace phongcl
