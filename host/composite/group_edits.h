#pragma once
// Which of a render's light groups an edited scene changed, and how: what decides whether a group's
// rendered pass is kept, scaled or replaced by phongcl's shading (composite/composite.h). The scene's
// "rendered" lights are the lights as rendered; its "lights" as the artist now has them.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "../scene/scene.h"

namespace phongcl {

enum class GroupChange {
  unchanged,  // the rendered pass as it is
  scaled,     // only colours changed, every light of the group by the same factor per channel: the pass scaled
  reshaded,   // anything else (moved, turned, added, removed, resized): phongcl shades the group
};

struct GroupEdit {
  std::string group;
  GroupChange change = GroupChange::unchanged;
  glm::dvec3 scale{1.0};  // scaled: the factor per channel
};

const char* to_string(GroupChange change);  // "unchanged", "scaled", "re-shaded"

// The lights of one group ("": those in none): its point, spot and directional lights, then its area lights.
struct GroupLights {
  std::vector<Light> lights;
  std::vector<AreaLight> area_lights;

  bool operator==(const GroupLights&) const = default;
};
GroupLights lights_of(const std::string& group, const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights);

// One entry per light group of either list, in the order of light_groups() over the edited lights,
// then groups only the render had. InputError naming the scene file when it has no "rendered", or
// when a light outside every group was edited, added or removed (its light is part of the render's
// Combined pass and cannot be taken out of it).
std::vector<GroupEdit> group_edits(const Scene& scene);

}  // namespace phongcl
