#pragma once
// Colours in from other spaces: the G-buffer's colour passes (--gbuffer-space) and the scene's
// colours ("color_space") become working-space values before shading. Installed with the public API.
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "../gbuffer/gbuffer.h"
#include "../scene/scene.h"
#include "color_config.h"

namespace phongcl {

// From one of the config's colour spaces (or roles) into another, by default its working space
// (exact: no approximated curves).
class ColorConversion {
 public:
  // InputError naming `option` and listing the config's spaces when `from` or `to` is not one of them.
  ColorConversion(const ColorConfig& config, const std::string& from, const std::string& option,
                  const std::string& to = "scene_linear");
  ~ColorConversion();
  ColorConversion(ColorConversion&&) noexcept;

  bool is_identity() const;
  glm::dvec3 operator()(const glm::dvec3& color) const;
  // In place, each plane width * height values, on every core.
  void convert(Planes3& planes) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The scene's colours (lights, materials' ka kd ks, ambient, background) from scene.color_space
// into the working space, then scene.color_space emptied; nothing when it is empty. InputError
// naming the scene file when a colour leaves the working space's gamut (a negative component: a
// light or reflectance cannot be negative).
void convert_scene_colors(Scene& scene, const ColorConfig& config);

// The G-buffer's colour passes (per-pixel ka, kd and ks: Blender's DiffCol and GlossCol; the
// beauty pass) from `space` into the working space. Out-of-gamut values stay as they come.
void convert_gbuffer_colors(GBuffer& gbuffer, const ColorConfig& config, const std::string& space);

}  // namespace phongcl
