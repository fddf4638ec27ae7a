// Validating a G-buffer's material indices against the scene before anything is shaded.
#include <cmath>
#include <sstream>
#include <string>

#include "common/error.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/material_check.h"

namespace phongcl {

namespace {

// Pixel coordinates as the file states them (the data window may not start at 0, 0).
std::string pixel_name(const GBuffer& g, std::size_t i) {
  const auto width = static_cast<std::size_t>(g.width);
  return "pixel (" + std::to_string(g.data_window.x_min + static_cast<int>(i % width)) + ", " +
         std::to_string(g.data_window.y_min + static_cast<int>(i / width)) + "): ";
}

std::string number(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

void check_materials(const GBuffer& g, std::size_t material_count) {
  // With every material parameter stored per pixel the table is not consulted: the index only
  // marks the pixel as shaded.
  const bool table_needed = !(g.has_per_pixel_ka() && g.has_per_pixel_kd() && g.has_per_pixel_ks() &&
                              g.has_per_pixel_shininess());
  const bool shininess_stored = g.has_per_pixel_shininess();
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    // The cheap tests first: classify_pixel (is the pixel shaded at all?) only where one fails.
    const float material = g.material[i];
    const bool suspicious = material != std::floor(material) ||
                            (table_needed && static_cast<double>(material) >= static_cast<double>(material_count)) ||
                            (shininess_stored && g.shininess[i] < 0.0f);
    if (!suspicious || classify_pixel(g, i) != PixelClass::shaded) continue;
    if (material != std::floor(material))
      throw InputError(g.source, pixel_name(g, i) + "material index " + number(material) + " is not an integer");
    if (table_needed && static_cast<double>(material) >= static_cast<double>(material_count))
      throw InputError(g.source, pixel_name(g, i) + "material index " + number(material) +
                                     " out of range (scene has " + std::to_string(material_count) +
                                     " materials)");
    if (shininess_stored && g.shininess[i] < 0.0f)
      throw InputError(g.source, pixel_name(g, i) + "shininess " + number(g.shininess[i]) + " is negative");
  }
}

void MaterialCheck::check(const GBuffer& gbuffer, std::size_t material_count) const {
  std::size_t passed = smallest_passing_.load();
  if (material_count >= passed) return;
  check_materials(gbuffer, material_count);
  while (material_count < passed && !smallest_passing_.compare_exchange_weak(passed, material_count)) {
  }
}

}  // namespace phongcl
