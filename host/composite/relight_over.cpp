#include "composite/relight_over.h"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>

#include "common/error.h"

namespace phongcl {

namespace {

// phongcl's diffuse and specular light of the lights of `group` alone, or none when it has none.
std::optional<GroupTerms> shade_group(Relighter& relighter, const std::string& group, const std::vector<Light>& lights,
                                      const std::vector<AreaLight>& area_lights) {
  std::vector<Light> its_lights;
  std::vector<AreaLight> its_area_lights;
  std::copy_if(lights.begin(), lights.end(), std::back_inserter(its_lights), [&](const Light& l) { return l.group == group; });
  std::copy_if(area_lights.begin(), area_lights.end(), std::back_inserter(its_area_lights),
               [&](const AreaLight& l) { return l.group == group; });
  if (its_lights.empty() && its_area_lights.empty()) return std::nullopt;
  relighter.set_lights(its_lights);
  relighter.set_area_lights(its_area_lights);
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
  try {
    for (const GroupEdit& edit : result.edits)
      if (edit.change == GroupChange::reshaded)
        changed[edit.group] = {shade_group(relighter, edit.group, rendered.lights, rendered.area_lights),
                               shade_group(relighter, edit.group, edited.lights, edited.area_lights)};
  } catch (...) {
    relighter.set_lights(held.lights);
    relighter.set_area_lights(held.area_lights);
    throw;
  }
  relighter.set_lights(held.lights);
  relighter.set_area_lights(held.area_lights);
  try {
    result.composite = composite_over(passes, result.edits, changed);
  } catch (const std::invalid_argument& error) {
    throw InputError(render, error.what());
  }
  return result;
}

}  // namespace phongcl
