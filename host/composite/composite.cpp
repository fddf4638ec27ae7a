#include "composite/composite.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/host_threads.h"

namespace phongcl {

namespace {

constexpr std::size_t kPixelsPerRange = 4096;

void require_size(const Image* image, const Image& render, const std::string& what) {
  if (image != nullptr && (image->width != render.width || image->height != render.height))
    throw std::invalid_argument(what + " is " + std::to_string(image->width) + " x " + std::to_string(image->height) +
                                ", the render " + std::to_string(render.width) + " x " + std::to_string(render.height));
}

// out += gain * (added - taken), channel by channel; a missing image counts as black.
void add_change(Image& out, const glm::vec3& gain, const Image* added, const Image* taken) {
  for_each_core_range(out.pixel_count(), kPixelsPerRange, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      float* pixel = out.pixel(i);
      for (int c = 0; c < 3; ++c)
        pixel[c] += gain[c] * ((added ? added->pixel(i)[c] : 0.0f) - (taken ? taken->pixel(i)[c] : 0.0f));
    }
  });
}

// `canvas` holding the render's Combined pass, its memory kept when it has the size already.
Image copy_of(const Image& combined, Image canvas) {
  if (canvas.rgba.size() != combined.rgba.size()) return combined;
  canvas.width = combined.width, canvas.height = combined.height;
  canvas.data_window = combined.data_window, canvas.display_window = combined.display_window;
  for_each_core_range(combined.rgba.size(), 4 * kPixelsPerRange, [&](std::size_t, std::size_t begin, std::size_t end) {
    std::copy(combined.rgba.begin() + begin, combined.rgba.begin() + end, canvas.rgba.begin() + begin);
  });
  return canvas;
}

}  // namespace

Image composite_over(const RenderPasses& render, const std::vector<GroupEdit>& edits,
                     const std::map<std::string, ChangedGroup>& changed, Image canvas) {
  Image image = copy_of(render.combined, std::move(canvas));
  for (const GroupEdit& edit : edits) {
    if (edit.change == GroupChange::unchanged) continue;
    const auto found = render.group_passes.find(edit.group);
    const Image* pass = found == render.group_passes.end() ? nullptr : &found->second;
    require_size(pass, render.combined, "the pass of '" + edit.group + "'");
    if (edit.change == GroupChange::scaled) {
      if (pass == nullptr) throw std::invalid_argument("light group '" + edit.group + "' has no rendered pass to scale");
      add_change(image, glm::vec3(edit.scale - 1.0), pass, nullptr);
      continue;
    }
    const auto shaded = changed.find(edit.group);
    if (shaded == changed.end()) throw std::invalid_argument("no shading of the changed light group '" + edit.group + "'");
    const ChangedGroup& group = shaded->second;
    for (const Image* light : {group.then, group.now})
      require_size(light, render.combined, "phongcl's image of '" + edit.group + "'");
    if (group.now == nullptr)
      add_change(image, glm::vec3(1.0f), nullptr, pass);  // its lights are gone: so is its light
    else if (pass != nullptr && group.then != nullptr)
      add_change(image, glm::vec3(1.0f), group.now, group.then);
    else if (pass == nullptr)
      add_change(image, glm::vec3(1.0f), group.now, nullptr);  // a group new to the render
    else
      throw std::invalid_argument("no shading of light group '" + edit.group + "' as rendered");
  }
  return image;
}

}  // namespace phongcl
