#include "reference/reference.h"

#include <vector>

namespace phongcl {

Image reference_image(const Scene& scene, const GBuffer& gbuffer, const LightReach& reaches,
                      const SoftVisibility& soft, ReferenceTermImages* terms) {
  Image image = image_like(gbuffer);
  if (terms) terms->ambient = terms->diffuse = terms->specular = image_like(gbuffer);
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    float* out = image.pixel(i);
    if (classify_pixel(gbuffer, i) == PixelClass::shaded) {
      const ShadingTerms shaded = reference_shade_point(scene, reference_surface(scene, gbuffer, i), reaches, soft);
      // IEEE round-to-nearest: +Inf exactly when the double colour overflows float, never earlier.
      // Edge policy: colour premultiplied by the pixel's coverage, which is its alpha.
      const double coverage = gbuffer.has_coverage() ? gbuffer.coverage[i] : 1.0;
      auto put = [&](float* pixel, const glm::dvec3& color) {
        for (int c = 0; c < 3; ++c) pixel[c] = static_cast<float>(color[c] * coverage);
        pixel[3] = static_cast<float>(coverage);
      };
      put(out, shaded.total());
      if (terms) {
        put(terms->ambient.pixel(i), shaded.ambient);
        put(terms->diffuse.pixel(i), shaded.diffuse);
        put(terms->specular.pixel(i), shaded.specular);
      }
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
