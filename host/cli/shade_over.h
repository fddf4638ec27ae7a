#pragma once
// shade --over RENDER: the frame relit over the render itself (composite/composite.h). The render's
// light-group passes are read and the edited groups composited into its Combined pass.
#include <string>

#include <phongcl/relighter.hpp>

#include "image/image.h"
#include "scene/scene.h"

namespace phongcl::cli {

struct OverResult {
  Image image;
  std::string summary;  // "render.exr (view layer ViewLayer): key moved (fit gain ..., residual ...), fill scaled x(2, 2, 2), rim unchanged"
};

// `relighter` holds the frame (with terms on): for each changed group it shades the group's lights
// alone, as rendered and as edited (composite/group_fit.h), and keeps the last lights it shaded.
// InputError naming the render or the scene for what a composite cannot use
// (composite/group_edits.h, composite/render_passes.h), or a render of another size than the G-buffer.
OverResult shade_over(const std::string& render_file, const Scene& scene, Relighter& relighter);

}  // namespace phongcl::cli
