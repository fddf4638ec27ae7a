#include "composite/relight_over.h"

#include <algorithm>
#include <stdexcept>

#include "common/error.h"

namespace phongcl {

namespace {

// The lights without their group: shaded alone, a group's image would only repeat the frame's.
GroupLights ungrouped(GroupLights lights) {
  for (Light& light : lights.lights) light.group.clear();
  for (AreaLight& light : lights.area_lights) light.group.clear();
  return lights;
}

// The materials whose light is the fitted light: diffuse and specular colours times the fit's gains,
// no ambient.
std::vector<Material> fitted(std::vector<Material> materials, const std::optional<GroupFit>& fit) {
  for (Material& material : materials) {
    material.ka = glm::dvec3(0.0);
    if (fit) material.kd *= fit->diffuse_gain, material.ks *= fit->specular_gain;
  }
  return materials;
}

}  // namespace

RenderCompositor::RenderCompositor(std::filesystem::path render)
    : file_(std::move(render)), passes_(read_render_passes(file_, {})) {}

bool RenderCompositor::shade_group(Relighter& relighter, const GroupLights& lights,
                                   const std::vector<Material>& materials, Image& light) {
  if (lights.lights.empty() && lights.area_lights.empty()) return false;
  const GroupLights alone = ungrouped(lights);
  relighter.set_materials(materials);
  relighter.set_lights(alone.lights);
  relighter.set_area_lights(alone.area_lights);
  relighter.set_environment(std::nullopt);  // a group alone: composites do not relight the world
  if (light.width != relighter.width() || light.height != relighter.height()) light = Image(relighter.width(), relighter.height());
  relighter.shade_into(light.rgba.data(), light.rgba.size());
  return true;
}

const RenderCompositor::RenderedGroup& RenderCompositor::rendered_group(Relighter& relighter, const std::string& group,
                                                                        const GroupLights& lights) {
  const Scene& held = relighter.scene();
  const auto kept = rendered_.find(group);
  if (kept != rendered_.end() && kept->second.lights == lights && kept->second.materials == held.materials &&
      kept->second.eye == held.camera.eye)
    return kept->second;
  RenderedGroup rendered{lights, held.materials, held.camera.eye, std::nullopt, std::nullopt};
  if (lights.lights.empty() && lights.area_lights.empty()) return rendered_[group] = std::move(rendered);
  if (const auto pass = passes_.group_passes.find(group); pass != passes_.group_passes.end()) {
    const GroupLights alone = ungrouped(lights);
    relighter.set_lights(alone.lights);
    relighter.set_area_lights(alone.area_lights);
    relighter.set_environment(std::nullopt);  // a group alone: composites do not relight the world
    TermImages terms;
    relighter.shade(terms);
    rendered.fit = fit_group(pass->second, {std::move(terms.diffuse), std::move(terms.specular)});
  }
  rendered.light.emplace();
  shade_group(relighter, lights, fitted(rendered.materials, rendered.fit), *rendered.light);
  return rendered_[group] = std::move(rendered);
}

RelitOver RenderCompositor::relight(Relighter& relighter, const Scene& edited, Image canvas) {
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
  const auto give_back = [&] {
    relighter.set_materials(held.materials);
    relighter.set_lights(held.lights);
    relighter.set_area_lights(held.area_lights);
    relighter.set_environment(held.environment);
  };
  try {
    for (const GroupEdit& edit : result.edits) {
      if (edit.change != GroupChange::reshaded) continue;
      const RenderedGroup& then =
          rendered_group(relighter, edit.group, lights_of(edit.group, rendered.lights, rendered.area_lights));
      Image& now = edited_[edit.group];
      const bool lit = shade_group(relighter, lights_of(edit.group, edited.lights, edited.area_lights),
                                   fitted(then.materials, then.fit), now);
      changed[edit.group] = {then.light ? &*then.light : nullptr, lit ? &now : nullptr};
      if (then.fit) result.fits.emplace(edit.group, *then.fit);
    }
  } catch (...) {
    give_back();
    throw;
  }
  give_back();
  try {
    result.image = composite_over(passes_, result.edits, changed, std::move(canvas));
  } catch (const std::invalid_argument& error) {
    throw InputError(file_, error.what());
  }
  return result;
}

RelitOver relight_over(Relighter& relighter, const std::filesystem::path& render, const Scene& edited) {
  return RenderCompositor(render).relight(relighter, edited);
}

}  // namespace phongcl
