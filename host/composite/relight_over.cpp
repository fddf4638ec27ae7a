#include "composite/relight_over.h"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>

#include "common/error.h"

namespace phongcl {

namespace {

// phongcl's diffuse and specular light of `lights` alone (one group's), or none when there are none.
std::optional<GroupTerms> shade_group(Relighter& relighter, const GroupLights& lights) {
  if (lights.lights.empty() && lights.area_lights.empty()) return std::nullopt;
  relighter.set_lights(lights.lights);
  relighter.set_area_lights(lights.area_lights);
  TermImages terms;
  relighter.shade(terms);
  return GroupTerms{std::move(terms.diffuse), std::move(terms.specular)};
}

}  // namespace

RelitOver relight_over(Relighter& relighter, const std::filesystem::path& render, const Scene& edited) {
  RelitOver result;
  result.edits = group_edits(edited);
  const RenderedLights& rendered = *edited.rendered;
  const std::vector<std::string> rendered_groups = light_groups(rendered.lights, rendered.area_lights);
  // Passes are read for the groups whose rendered light is scaled or changed; those changed are shaded.
  std::vector<std::string> needed;
  for (const GroupEdit& edit : result.edits)
    if (edit.change != GroupChange::unchanged &&
        std::find(rendered_groups.begin(), rendered_groups.end(), edit.group) != rendered_groups.end())
      needed.push_back(edit.group);
  const RenderPasses passes = read_render_passes(render, needed);
  result.view_layer = passes.layer.empty() ? "" : passes.layer.substr(0, passes.layer.size() - 1);
  std::map<std::string, ChangedGroup> changed;
  const Scene held = relighter.scene();
  const auto give_lights_back = [&] {
    relighter.set_lights(held.lights);
    relighter.set_area_lights(held.area_lights);
  };
  try {
    for (const GroupEdit& edit : result.edits)
      if (edit.change == GroupChange::reshaded)
        changed[edit.group] = {shade_group(relighter, lights_of(edit.group, rendered.lights, rendered.area_lights)),
                               shade_group(relighter, lights_of(edit.group, edited.lights, edited.area_lights))};
  } catch (...) {
    give_lights_back();
    throw;
  }
  give_lights_back();
  try {
    result.composite = composite_over(passes, result.edits, changed);
  } catch (const std::invalid_argument& error) {
    throw InputError(render, error.what());
  }
  return result;
}

}  // namespace phongcl
