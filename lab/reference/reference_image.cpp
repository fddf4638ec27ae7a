#include "reference/reference.h"

#include <vector>

namespace phongcl {

Image reference_image(const Scene& scene, const GBuffer& gbuffer, const LightReach& reaches,
                      const SoftVisibility& soft) {
  Image image = image_like(gbuffer);
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    float* out = image.pixel(i);
    if (classify_pixel(gbuffer, i) == PixelClass::shaded) {
      const glm::dvec3 color = reference_shade_point(scene, reference_surface(scene, gbuffer, i), reaches, soft).total();
      // IEEE round-to-nearest: +Inf exactly when the double colour overflows float, never earlier.
      // Edge policy: colour premultiplied by the pixel's coverage, which is its alpha.
      const double coverage = gbuffer.has_coverage() ? gbuffer.coverage[i] : 1.0;
      for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(color[c] * coverage);
      out[3] = static_cast<float>(coverage);
    } else {
      for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(scene.background[c]);
      out[3] = 0.0f;
    }
  }
  return image;
}

Scene reference_group_scene(const Scene& scene, const std::string& group) {
  Scene alone = scene;
  alone.ambient = glm::dvec3(0.0);
  std::erase_if(alone.lights, [&](const Light& light) { return light.group != group; });
  std::erase_if(alone.area_lights, [&](const AreaLight& light) { return light.group != group; });
  if (alone.environment && alone.environment->group != group) alone.environment.reset();
  return alone;
}

}  // namespace phongcl
