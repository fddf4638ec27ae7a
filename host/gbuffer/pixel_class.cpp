// Which pixels get shaded: one decision shared by the kernel's packing and the reference.
#include <cmath>
#include <vector>

#include "gbuffer/gbuffer.h"

namespace phongcl {

namespace {

bool finite_at(const Planes3& planes, std::size_t i) {
  return std::isfinite(planes[0][i]) && std::isfinite(planes[1][i]) && std::isfinite(planes[2][i]);
}

bool per_pixel_material_finite(const GBuffer& g, std::size_t i) {
  return (!g.has_per_pixel_ka() || finite_at(g.ka, i)) && (!g.has_per_pixel_kd() || finite_at(g.kd, i)) &&
         (!g.has_per_pixel_ks() || finite_at(g.ks, i)) &&
         (!g.has_per_pixel_shininess() || std::isfinite(g.shininess[i]));
}

// 0 in poison[t] where the plane's value is finite, NaN otherwise: x * 0 is NaN exactly for NaN
// and the infinities, and without branches the loop vectorises.
void add_poison(const Plane& plane, std::size_t first, std::size_t count, float* poison) {
  for (std::size_t t = 0; t < count; ++t) poison[t] += plane[first + t] * 0.0f;
}

}  // namespace

PixelClass classify_pixel(const GBuffer& g, std::size_t i) {
  // The material decides background first: background pixels often carry P/N at infinity (a ray
  // miss), and that is not an error. A NaN material cannot say "background", so it is an error.
  const float material = g.material[i];
  if (!std::isfinite(material)) return PixelClass::nonfinite_material;
  if (material < 0.0f) return PixelClass::background;
  if (!finite_at(g.position, i)) return PixelClass::nonfinite_position;
  if (!finite_at(g.normal, i)) return PixelClass::nonfinite_normal;
  if (!per_pixel_material_finite(g, i)) return PixelClass::nonfinite_material;
  return PixelClass::shaded;
}

void classify_pixels(const GBuffer& g, std::size_t first, std::size_t count, PixelClass* classes) {
  // Every value finite and a material >= 0 is shaded; that test runs branch-free over whole
  // planes, and classify_pixel names the class of the rest.
  std::vector<float> poison(count, 0.0f);
  for (const Planes3* group : {&g.position, &g.normal, &g.ka, &g.kd, &g.ks}) {
    for (const Plane& plane : *group) {
      if (!plane.empty()) add_poison(plane, first, count, poison.data());
    }
  }
  if (g.has_per_pixel_shininess()) add_poison(g.shininess, first, count, poison.data());
  for (std::size_t t = 0; t < count; ++t) {
    const float material = g.material[first + t];
    const bool shaded = poison[t] == 0.0f && material >= 0.0f && std::isfinite(material);
    classes[t] = shaded ? PixelClass::shaded : classify_pixel(g, first + t);
  }
}

}  // namespace phongcl
