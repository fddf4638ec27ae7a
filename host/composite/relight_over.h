#pragma once
// The frame relit over a render, end to end: which groups the edited scene changed, the render's passes
// of those, phongcl's terms of each changed group alone (as rendered and as edited), the composite.
// What `phongcl shade --over`, serve's page over a render and the Python module run; a library user
// calls it with a Relighter that holds the frame.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <phongcl/relighter.hpp>

#include "composite.h"
#include "group_edits.h"
#include "group_fit.h"
#include "render_passes.h"

namespace phongcl {

struct RelitOver {
  Image image;                           // the composite
  std::vector<GroupEdit> edits;          // per light group: unchanged, scaled or re-shaded
  std::map<std::string, GroupFit> fits;  // per re-shaded group the render had
  std::string view_layer;                // the render's view layer ("" when its passes have none)
};

// A render held for relighting over it again and again (serve's drag, a loop in a program): its passes
// are read once, and each group's fit to its pass and phongcl's fitted light of its lights as rendered
// are kept while the group's rendered lights and the Relighter's materials and eye stay as they were.
// A frame then costs one shade of each changed group's lights as edited, and the composite. The fit's
// gains go into the materials (kd times the diffuse gain, ks times the specular's, ka 0), so that one
// shade gives the group's fitted light: the same as fitting its terms, at a quarter of the download.
class RenderCompositor {
 public:
  // Reads the render's Combined pass and every light group's pass (composite/render_passes.h).
  explicit RenderCompositor(std::filesystem::path render);

  // `relighter`: the G-buffer of the render, with RelighterOptions::terms on (std::logic_error
  // otherwise); it keeps the lights it had. `edited`: the scene with its "rendered" lights (a
  // Relighter's scene() after set_lights keeps those it was made with). InputError naming the render
  // or the scene for what a composite cannot use (composite/group_edits.h), a changed group without
  // a pass, or a render of another size than the G-buffer. The image is made in `canvas` when it has
  // the render's size (an earlier composite nobody reads any more).
  RelitOver relight(Relighter& relighter, const Scene& edited, Image canvas = {});

  // The terms kept are of one Relighter with its options: call this when another one shades.
  void forget_rendered_terms() { rendered_.clear(); }

  const std::filesystem::path& file() const { return file_; }
  const RenderPasses& passes() const { return passes_; }

 private:
  // A group as rendered: what its fit and light were made with, the fit (none without a pass) and
  // phongcl's fitted light of it (none when it had no lights).
  struct RenderedGroup {
    GroupLights lights;
    std::vector<Material> materials;
    glm::dvec3 eye{0.0};
    std::optional<GroupFit> fit;
    std::optional<Image> light;
  };
  const RenderedGroup& rendered_group(Relighter& relighter, const std::string& group, const GroupLights& lights);
  // phongcl's light of `lights` alone with `materials` into `light`; false when there are no lights.
  bool shade_group(Relighter& relighter, const GroupLights& lights, const std::vector<Material>& materials, Image& light);

  std::filesystem::path file_;
  RenderPasses passes_;
  std::map<std::string, RenderedGroup> rendered_;
  std::map<std::string, Image> edited_;  // each changed group's light as edited, its memory kept from frame to frame
};

// The composite of one frame: RenderCompositor(render).relight(relighter, edited).
RelitOver relight_over(Relighter& relighter, const std::filesystem::path& render, const Scene& edited);

}  // namespace phongcl
