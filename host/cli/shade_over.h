#pragma once
// shade --over RENDER: the frame relit over the render itself (composite/relight_over.h), and a line
// that says what became of each light group.
#include <string>

#include <phongcl/relighter.hpp>

#include "image/image.h"
#include "scene/scene.h"

namespace phongcl::cli {

struct OverResult {
  Image image;
  std::string summary;  // "render.exr (view layer ViewLayer): key changed by phongcl's change (fit: ...), rim unchanged"
};

// As relight_over(): `relighter` holds the frame, with terms on.
OverResult shade_over(const std::string& render_file, const Scene& scene, Relighter& relighter);

}  // namespace phongcl::cli
