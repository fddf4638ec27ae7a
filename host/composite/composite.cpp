#include "composite/composite.h"

#include <stdexcept>
#include <string>

namespace phongcl {

namespace {

void require_size(const Image* image, const Image& render, const std::string& what) {
  if (image != nullptr && (image->width != render.width || image->height != render.height))
    throw std::invalid_argument(what + " is " + std::to_string(image->width) + " x " + std::to_string(image->height) +
                                ", the render " + std::to_string(render.width) + " x " + std::to_string(render.height));
}

// out += gain * (added - taken), channel by channel; a missing image counts as black.
void add_change(Image& out, const glm::dvec3& gain, const Image* added, const Image* taken) {
  for (std::size_t i = 0; i < out.pixel_count(); ++i) {
    float* pixel = out.pixel(i);
    for (int c = 0; c < 3; ++c) {
      const float change = (added ? added->pixel(i)[c] : 0.0f) - (taken ? taken->pixel(i)[c] : 0.0f);
      pixel[c] += static_cast<float>(gain[c] * change);
    }
  }
}

const Image* diffuse_of(const GroupTerms* terms) { return terms ? &terms->diffuse : nullptr; }
const Image* specular_of(const GroupTerms* terms) { return terms ? &terms->specular : nullptr; }

}  // namespace

Composite composite_over(const RenderPasses& render, const std::vector<GroupEdit>& edits,
                         const std::map<std::string, ChangedGroup>& changed) {
  Composite result{render.combined, {}};
  for (const GroupEdit& edit : edits) {
    if (edit.change == GroupChange::unchanged) continue;
    const auto found = render.group_passes.find(edit.group);
    const Image* pass = found == render.group_passes.end() ? nullptr : &found->second;
    require_size(pass, render.combined, "the pass of '" + edit.group + "'");
    if (edit.change == GroupChange::scaled) {
      if (pass == nullptr) throw std::invalid_argument("light group '" + edit.group + "' has no rendered pass to scale");
      add_change(result.image, edit.scale - 1.0, pass, nullptr);
      continue;
    }
    const auto terms = changed.find(edit.group);
    if (terms == changed.end()) throw std::invalid_argument("no shading of the changed light group '" + edit.group + "'");
    const ChangedGroup& group = terms->second;
    const GroupTerms* now = group.now ? &*group.now : nullptr;
    for (const GroupTerms* shaded : {group.then, now})
      for (const Image* image : {diffuse_of(shaded), specular_of(shaded)})
        require_size(image, render.combined, "phongcl's image of '" + edit.group + "'");
    if (now == nullptr) {
      add_change(result.image, glm::dvec3(1.0), nullptr, pass);  // its lights are gone: so is its light
    } else if (pass != nullptr && group.then != nullptr) {
      const GroupFit fit = group.fit ? *group.fit : fit_group(*pass, *group.then);
      result.fits.emplace(edit.group, fit);
      add_change(result.image, fit.diffuse_gain, &now->diffuse, &group.then->diffuse);
      add_change(result.image, fit.specular_gain, &now->specular, &group.then->specular);
    } else if (pass == nullptr) {
      add_change(result.image, glm::dvec3(1.0), &now->diffuse, nullptr);  // a group new to the render
      add_change(result.image, glm::dvec3(1.0), &now->specular, nullptr);
    } else {
      throw std::invalid_argument("no shading of light group '" + edit.group + "' as rendered");
    }
  }
  return result;
}

}  // namespace phongcl
