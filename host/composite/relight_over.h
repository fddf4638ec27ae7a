#pragma once
// The frame relit over a render, end to end: which groups the edited scene changed, the render's passes
// of those, phongcl's terms of each changed group alone (as rendered and as edited), the composite.
// What `phongcl shade --over`, serve's page over a render and the Python module run; a library user
// calls it with a Relighter that holds the frame.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <phongcl/relighter.hpp>

#include "composite.h"
#include "group_edits.h"
#include "render_passes.h"

namespace phongcl {

struct RelitOver {
  Composite composite;           // the image, and the fit of each changed group
  std::vector<GroupEdit> edits;  // per light group: unchanged, scaled or re-shaded
  std::string view_layer;        // the render's view layer ("" when its passes have none)
};

// A render held for relighting over it again and again (serve's drag, a loop in a program): its passes
// are read once, and phongcl's terms of each group with its lights as rendered, with their fit to the
// group's pass, are kept while the group's rendered lights and the Relighter's materials and eye stay
// as they were. A frame then costs the changed groups' shading as edited and the composite.
class RenderCompositor {
 public:
  // Reads the render's Combined pass and every light group's pass (composite/render_passes.h).
  explicit RenderCompositor(std::filesystem::path render);

  // `relighter`: the G-buffer of the render, with RelighterOptions::terms on (std::logic_error
  // otherwise); it keeps the lights it had. `edited`: the scene with its "rendered" lights (a
  // Relighter's scene() after set_lights keeps those it was made with). InputError naming the render
  // or the scene for what a composite cannot use (composite/group_edits.h), a changed group without
  // a pass, or a render of another size than the G-buffer.
  RelitOver relight(Relighter& relighter, const Scene& edited);

  // The terms kept are of one Relighter with its options: call this when another one shades.
  void forget_rendered_terms() { rendered_.clear(); }

  const std::filesystem::path& file() const { return file_; }
  const RenderPasses& passes() const { return passes_; }

 private:
  // phongcl's terms of one group as rendered, and what they were shaded with.
  struct RenderedGroup {
    GroupLights lights;
    std::vector<Material> materials;
    glm::dvec3 eye{0.0};
    std::unique_ptr<const GroupTerms> terms;  // null: the group had no lights
    std::unique_ptr<const GroupFit> fit;      // null: not fitted yet, or no pass to fit
  };
  const RenderedGroup& rendered_group(Relighter& relighter, const std::string& group, const GroupLights& lights);

  std::filesystem::path file_;
  RenderPasses passes_;
  std::map<std::string, RenderedGroup> rendered_;
};

// The composite of one frame: RenderCompositor(render).relight(relighter, edited).
RelitOver relight_over(Relighter& relighter, const std::filesystem::path& render, const Scene& edited);

}  // namespace phongcl
