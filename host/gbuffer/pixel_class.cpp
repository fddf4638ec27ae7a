// Which pixels get shaded: one decision shared by the kernel's packing and the reference.
#include <cmath>

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

}  // namespace phongcl
