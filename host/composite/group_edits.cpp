#include "composite/group_edits.h"

#include <algorithm>

#include "common/error.h"

namespace phongcl {

namespace {

template <class AnyLight>
bool same_but_colour(AnyLight edited, const AnyLight& rendered) {
  edited.color = rendered.color;
  return edited == rendered;
}

// The factor that takes every rendered colour to its edited one, channel by channel; false when the
// lights differ otherwise, or a channel's factor differs between lights (or a dark channel lit up).
bool uniform_scale(const GroupLights& edited, const GroupLights& rendered, glm::dvec3& scale) {
  if (edited.lights.size() != rendered.lights.size() || edited.area_lights.size() != rendered.area_lights.size())
    return false;
  std::vector<std::pair<glm::dvec3, glm::dvec3>> colours;  // (edited, rendered)
  for (std::size_t i = 0; i < edited.lights.size(); ++i) {
    if (!same_but_colour(edited.lights[i], rendered.lights[i])) return false;
    colours.emplace_back(edited.lights[i].color, rendered.lights[i].color);
  }
  for (std::size_t i = 0; i < edited.area_lights.size(); ++i) {
    if (!same_but_colour(edited.area_lights[i], rendered.area_lights[i])) return false;
    colours.emplace_back(edited.area_lights[i].color, rendered.area_lights[i].color);
  }
  for (int c = 0; c < 3; ++c) {
    bool known = false;
    scale[c] = 1.0;
    for (const auto& [now, then] : colours) {
      if (then[c] == 0.0) {
        if (now[c] != 0.0) return false;  // no rendered light in this channel to scale
        continue;
      }
      const double factor = now[c] / then[c];
      if (known && factor != scale[c]) return false;
      scale[c] = factor;
      known = true;
    }
  }
  return true;
}

}  // namespace

GroupLights lights_of(const std::string& group, const std::vector<Light>& lights, const std::vector<AreaLight>& areas) {
  GroupLights result;
  std::copy_if(lights.begin(), lights.end(), std::back_inserter(result.lights), [&](const Light& l) { return l.group == group; });
  std::copy_if(areas.begin(), areas.end(), std::back_inserter(result.area_lights),
               [&](const AreaLight& l) { return l.group == group; });
  return result;
}

const char* to_string(GroupChange change) {
  switch (change) {
    case GroupChange::unchanged: return "unchanged";
    case GroupChange::scaled: return "scaled";
    case GroupChange::reshaded: return "re-shaded";
  }
  return "unchanged";
}

std::vector<GroupEdit> group_edits(const Scene& scene) {
  if (!scene.rendered)
    throw InputError(scene.source, "has no \"rendered\" lights: compositing over a render needs the lights as they "
                                   "were rendered (scripts/blender/export_scene.py writes them) to tell which light "
                                   "groups changed");
  const RenderedLights& rendered = *scene.rendered;
  if (lights_of("", scene.lights, scene.area_lights) != lights_of("", rendered.lights, rendered.area_lights))
    throw InputError(scene.source, "a light in no light group differs from the rendered ones: its light is part of "
                                   "the render's Combined pass and cannot be taken out; give it a group in Blender "
                                   "(Object > Shading > Light Group) and render again");
  std::vector<std::string> groups = light_groups(scene.lights, scene.area_lights);
  for (const std::string& group : light_groups(rendered.lights, rendered.area_lights))
    if (std::find(groups.begin(), groups.end(), group) == groups.end()) groups.push_back(group);

  std::vector<GroupEdit> edits;
  for (const std::string& group : groups) {
    const GroupLights now = lights_of(group, scene.lights, scene.area_lights);
    const GroupLights then = lights_of(group, rendered.lights, rendered.area_lights);
    GroupEdit edit{group};
    if (now == then)
      edit.change = GroupChange::unchanged;
    else if (uniform_scale(now, then, edit.scale))
      edit.change = GroupChange::scaled;
    else
      edit.change = GroupChange::reshaded;
    edits.push_back(edit);
  }
  return edits;
}

}  // namespace phongcl
