#include "shading/shadow_settings.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace phongcl {

std::string to_string(ShadowMode mode) {
  switch (mode) {
    case ShadowMode::automatic: return "auto";
    case ShadowMode::screen: return "screen";
    case ShadowMode::geometry: return "geometry";
    case ShadowMode::off: return "off";
  }
  return "auto";
}

ShadowMode parse_shadow_mode(const std::string& name) {
  for (ShadowMode mode : {ShadowMode::automatic, ShadowMode::screen, ShadowMode::geometry, ShadowMode::off})
    if (name == to_string(mode)) return mode;
  throw std::invalid_argument("unknown shadow mode '" + name + "' (auto, screen, geometry or off)");
}

double parse_shadow_thickness(const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (number.empty() || used != number.size() || !std::isfinite(value) || !(value > 0.0) || (percent && value > 1000.0))
    throw std::invalid_argument("shadow thickness '" + text +
                                "' is not a positive length in world units (0.25) or a percentage of the depth (6%)");
  return percent ? -value / 100.0 : value;
}

std::string format_shadow_thickness(double thickness) {
  char text[32];
  if (thickness < 0.0) std::snprintf(text, sizeof text, "%g%%", -thickness * 100.0);
  else std::snprintf(text, sizeof text, "%g", thickness);
  return text;
}

void check_shadow_settings(const ShadowSettings& settings) {
  if (settings.steps < 1 || settings.steps > 1024)
    throw std::invalid_argument("shadow steps must be 1 to 1024 (got " + std::to_string(settings.steps) + ")");
  if (!std::isfinite(settings.thickness) || settings.thickness == 0.0 || settings.thickness < -10.0)
    throw std::invalid_argument("shadow thickness must be a positive length or a percentage up to 1000% (got " +
                                format_shadow_thickness(settings.thickness) + ")");
  if (settings.rays < 1 || settings.rays > kMaxShadowRays)
    throw std::invalid_argument("shadow rays must be 1 to " + std::to_string(kMaxShadowRays) + " (got " +
                                std::to_string(settings.rays) + ")");
  if (settings.environment_rays < 1 || settings.environment_rays > kMaxEnvironmentRays)
    throw std::invalid_argument("environment rays must be 1 to " + std::to_string(kMaxEnvironmentRays) + " (got " +
                                std::to_string(settings.environment_rays) + ")");
}

int shadow_rays(const AreaLight& light, const ShadowSettings& settings) {
  return light.shadow_rays > 0 ? light.shadow_rays : settings.rays;
}

int shadow_rays(const EnvironmentLight& light, const ShadowSettings& settings) {
  return light.rays > 0 ? light.rays : settings.environment_rays;
}

int shadow_rays(const Light& light, const ShadowSettings& settings) {
  if (!light.has_size()) return 1;
  return light.shadow_rays > 0 ? light.shadow_rays : settings.rays;
}

}  // namespace phongcl
