#pragma once
// Relighting over the render itself: the render's Combined pass, with each changed light group's
// light changed. An unchanged group, the world and everything in no group stay exactly as rendered; a
// group whose lights only changed colour by one factor per channel is its pass scaled (as renderers'
// LightMix does: exact); for any other change the group's pass changes by phongcl's change of it,
// fitted to the pass (composite/group_fit.h): what the model leaves out stays as rendered.
#include <map>
#include <string>
#include <vector>

#include "group_edits.h"
#include "render_passes.h"
#include "../image/image.h"

namespace phongcl {

// phongcl's light of one re-shaded group alone, fitted to its pass, held by the caller (who may keep
// it from frame to frame): with the lights as rendered (nullptr for a group the render did not have)
// and as edited (nullptr when its lights are all gone). Shaded alike, so that where the lights add
// nothing (the background) the two are equal and their difference is 0.
struct ChangedGroup {
  const Image* then = nullptr;
  const Image* now = nullptr;
};

// Works on premultiplied values, so an edge pixel's new light is mixed as its coverage was rendered;
// alpha is the render's. `changed`: each re-shaded group's light, of the render's size. A group the
// render did not have adds phongcl's light; one whose lights are all gone takes its pass out. The
// image is made in `canvas` when it has the render's size (an earlier composite nobody reads any
// more: a new 1080p image's pages fault in on first write). std::invalid_argument when a size differs,
// or a scaled or re-shaded group that the render had has no pass or no light as rendered.
Image composite_over(const RenderPasses& render, const std::vector<GroupEdit>& edits,
                     const std::map<std::string, ChangedGroup>& changed, Image canvas = {});

}  // namespace phongcl
