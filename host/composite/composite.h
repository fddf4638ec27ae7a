#pragma once
// Relighting over the render itself: the render's Combined pass, with each changed light group's
// light changed. An unchanged group, the world and everything in no group stay exactly as rendered; a
// group whose lights only changed colour by one factor per channel is its pass scaled (as renderers'
// LightMix does: exact); for any other change the group's pass changes by phongcl's change of it,
// scaled by the gain that fits phongcl's shading of the rendered lights to the pass
// (composite/group_fit.h): what the model leaves out stays as rendered.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "group_edits.h"
#include "group_fit.h"
#include "render_passes.h"
#include "../image/image.h"

namespace phongcl {

struct Composite {
  Image image;
  std::map<std::string, GroupFit> fits;  // per changed group the render had
};

// phongcl's terms of one changed group, alone: with its lights as rendered (nullptr for a group the
// render did not have; held by the caller, who may keep them from frame to frame) and as edited (none
// when its lights are all gone). `fit`: the fit of `then` to the group's pass when the caller knows
// it already; nullptr: fitted here.
struct ChangedGroup {
  const GroupTerms* then = nullptr;
  std::optional<GroupTerms> now;
  const GroupFit* fit = nullptr;
};

// Works on premultiplied values, so an edge pixel's new light is mixed as its coverage was rendered;
// alpha is the render's. `changed`: the terms of each re-shaded group, of the render's size. A group
// the render did not have adds phongcl's shading; one whose lights are all gone takes its pass out.
// std::invalid_argument when a size differs, or a scaled or re-shaded group that the render had has no
// pass or no terms.
Composite composite_over(const RenderPasses& render, const std::vector<GroupEdit>& edits,
                         const std::map<std::string, ChangedGroup>& changed);

}  // namespace phongcl
