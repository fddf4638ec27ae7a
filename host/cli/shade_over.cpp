#include "cli/shade_over.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>

#include "common/error.h"
#include "composite/composite.h"

namespace phongcl::cli {

namespace {

std::string factors(const glm::dvec3& scale) {
  char text[96];
  std::snprintf(text, sizeof text, "x(%g, %g, %g)", scale.r, scale.g, scale.b);
  return text;
}

std::string describe(const GroupEdit& edit, const std::map<std::string, GroupFit>& fits) {
  switch (edit.change) {
    case GroupChange::unchanged: return edit.group + " unchanged";
    case GroupChange::scaled: return edit.group + " scaled " + factors(edit.scale);
    case GroupChange::reshaded: break;
  }
  const auto fit = fits.find(edit.group);
  if (fit == fits.end()) return edit.group + " shaded by phongcl";
  char residual[32];
  std::snprintf(residual, sizeof residual, "%.3g", fit->second.residual);
  return edit.group + " changed by phongcl's change (fit: diffuse " + factors(fit->second.diffuse_gain) + ", specular " +
         factors(fit->second.specular_gain) + ", residual " + residual + ")";
}

// phongcl's diffuse and specular light of the lights of `group` alone, or none when it has none.
std::optional<GroupTerms> shade_group(Relighter& relighter, const std::string& group, const std::vector<Light>& lights,
                                      const std::vector<AreaLight>& area_lights) {
  std::vector<Light> its_lights;
  std::vector<AreaLight> its_area_lights;
  for (const Light& light : lights)
    if (light.group == group) its_lights.push_back(light);
  for (const AreaLight& light : area_lights)
    if (light.group == group) its_area_lights.push_back(light);
  if (its_lights.empty() && its_area_lights.empty()) return std::nullopt;
  relighter.set_lights(its_lights);
  relighter.set_area_lights(its_area_lights);
  TermImages terms;
  relighter.shade(terms);
  return GroupTerms{std::move(terms.diffuse), std::move(terms.specular)};
}

}  // namespace

OverResult shade_over(const std::string& render_file, const Scene& scene, Relighter& relighter) {
  const std::vector<GroupEdit> edits = group_edits(scene);
  const RenderedLights& rendered = *scene.rendered;
  const std::vector<std::string> rendered_groups = light_groups(rendered.lights, rendered.area_lights);
  // Passes are read for the groups whose rendered light is scaled or changed; those changed are shaded.
  std::vector<std::string> needed;
  std::map<std::string, ChangedGroup> changed;
  for (const GroupEdit& edit : edits) {
    if (edit.change != GroupChange::unchanged &&
        std::find(rendered_groups.begin(), rendered_groups.end(), edit.group) != rendered_groups.end())
      needed.push_back(edit.group);
  }
  const RenderPasses passes = read_render_passes(render_file, needed);
  for (const GroupEdit& edit : edits)
    if (edit.change == GroupChange::reshaded)
      changed[edit.group] = {shade_group(relighter, edit.group, rendered.lights, rendered.area_lights),
                             shade_group(relighter, edit.group, scene.lights, scene.area_lights)};
  OverResult result;
  Composite composite;
  try {
    composite = composite_over(passes, edits, changed);
  } catch (const std::invalid_argument& error) {
    throw InputError(render_file, error.what());
  }
  result.image = std::move(composite.image);
  const std::string layer = passes.layer.empty() ? "" : " (view layer " + passes.layer.substr(0, passes.layer.size() - 1) + ")";
  std::string groups;
  for (const GroupEdit& edit : edits) groups += (groups.empty() ? "" : ", ") + describe(edit, composite.fits);
  result.summary = render_file + layer + (groups.empty() ? ": no light groups, the render as it is" : ": " + groups);
  return result;
}

}  // namespace phongcl::cli
