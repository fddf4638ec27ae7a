#include <string>

#include "common/error.h"
#include "reference/reference.h"

namespace phongcl {

namespace {

glm::dvec3 pixel_vec3(const Planes3& planes, std::size_t index) {
  // float -> double before any arithmetic: the reference sees exactly the stored values.
  return {static_cast<double>(planes[0][index]), static_cast<double>(planes[1][index]),
          static_cast<double>(planes[2][index])};
}

}  // namespace

SurfacePoint reference_surface(const Scene& scene, const GBuffer& gbuffer, std::size_t index) {
  SurfacePoint point;
  point.position = pixel_vec3(gbuffer.position, index);
  point.normal = pixel_vec3(gbuffer.normal, index);

  point.material = static_cast<int>(gbuffer.material[index]);
  const bool all_per_pixel = gbuffer.has_per_pixel_ka() && gbuffer.has_per_pixel_kd() &&
                             gbuffer.has_per_pixel_ks() && gbuffer.has_per_pixel_shininess();
  // With every group per pixel the table may be empty and the index is never used.
  if (!all_per_pixel) {
    const int material = static_cast<int>(gbuffer.material[index]);
    if (material < 0 || static_cast<std::size_t>(material) >= scene.materials.size())
      throw InputError(gbuffer.source, "pixel " + std::to_string(index) + ": material index " +
                                           std::to_string(material) + " is not in the scene's " +
                                           std::to_string(scene.materials.size()) + " materials");
    const Material& table = scene.materials[static_cast<std::size_t>(material)];
    point.ka = table.ka;
    point.kd = table.kd;
    point.ks = table.ks;
    point.shininess = table.shininess;
    // The model is never per pixel: the table's, where the table is consulted; else phong.
    point.specular_model = table.specular_model;
    if (table.specular_model == SpecularModel::principled) point.principled = table;
  }

  if (gbuffer.has_per_pixel_ka()) point.ka = pixel_vec3(gbuffer.ka, index);
  if (gbuffer.has_per_pixel_kd()) point.kd = pixel_vec3(gbuffer.kd, index);
  if (gbuffer.has_per_pixel_ks()) point.ks = pixel_vec3(gbuffer.ks, index);
  if (gbuffer.has_per_pixel_shininess()) point.shininess = static_cast<double>(gbuffer.shininess[index]);
  return point;
}

}  // namespace phongcl
