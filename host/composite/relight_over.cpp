#include "composite/relight_over.h"

#include <algorithm>
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

RenderCompositor::RenderCompositor(std::filesystem::path render)
    : file_(std::move(render)), passes_(read_render_passes(file_, {})) {}

const RenderCompositor::RenderedGroup& RenderCompositor::rendered_group(Relighter& relighter, const std::string& group,
                                                                        const GroupLights& lights) {
  const Scene& held = relighter.scene();
  const auto kept = rendered_.find(group);
  if (kept != rendered_.end() && kept->second.lights == lights && kept->second.materials == held.materials &&
      kept->second.eye == held.camera.eye)
    return kept->second;
  RenderedGroup shaded{lights, held.materials, held.camera.eye, nullptr, nullptr};
  if (std::optional<GroupTerms> terms = shade_group(relighter, lights)) {
    const auto pass = passes_.group_passes.find(group);
    if (pass != passes_.group_passes.end())
      shaded.fit = std::make_unique<const GroupFit>(fit_group(pass->second, *terms));
    shaded.terms = std::make_unique<const GroupTerms>(std::move(*terms));
  }
  return rendered_[group] = std::move(shaded);
}

RelitOver RenderCompositor::relight(Relighter& relighter, const Scene& edited) {
  const Image& combined = passes_.combined;
  if (combined.width != relighter.width() || combined.height != relighter.height())
    throw InputError(file_, "is " + std::to_string(combined.width) + " x " + std::to_string(combined.height) +
                                ", the G-buffer " + std::to_string(relighter.width()) + " x " +
                                std::to_string(relighter.height()) + ": composite over the render of this G-buffer");
  RelitOver result;
  result.edits = group_edits(edited);
  result.view_layer = passes_.layer.empty() ? "" : passes_.layer.substr(0, passes_.layer.size() - 1);
  const RenderedLights& rendered = *edited.rendered;
  const std::vector<std::string> rendered_groups = light_groups(rendered.lights, rendered.area_lights);
  // A group the render had needs its pass once its light is scaled or changed.
  for (const GroupEdit& edit : result.edits)
    if (edit.change != GroupChange::unchanged && passes_.group_passes.count(edit.group) == 0 &&
        std::find(rendered_groups.begin(), rendered_groups.end(), edit.group) != rendered_groups.end())
      throw missing_group_pass(file_, passes_, edit.group);
  std::map<std::string, ChangedGroup> changed;
  const Scene held = relighter.scene();
  const auto give_lights_back = [&] {
    relighter.set_lights(held.lights);
    relighter.set_area_lights(held.area_lights);
  };
  try {
    for (const GroupEdit& edit : result.edits)
      if (edit.change == GroupChange::reshaded) {
        const RenderedGroup& then =
            rendered_group(relighter, edit.group, lights_of(edit.group, rendered.lights, rendered.area_lights));
        changed[edit.group] = {then.terms.get(),
                               shade_group(relighter, lights_of(edit.group, edited.lights, edited.area_lights)),
                               then.fit.get()};
      }
  } catch (...) {
    give_lights_back();
    throw;
  }
  give_lights_back();
  try {
    result.composite = composite_over(passes_, result.edits, changed);
  } catch (const std::invalid_argument& error) {
    throw InputError(file_, error.what());
  }
  return result;
}

RelitOver relight_over(Relighter& relighter, const std::filesystem::path& render, const Scene& edited) {
  return RenderCompositor(render).relight(relighter, edited);
}

}  // namespace phongcl
