#pragma once
// How shadows are made (docs/shadows.md): the mode a caller chooses and the screen-space march's
// settings. A light casts shadows only when its "shadows" is true and the mode is not off.
#include <string>

#include "../scene/scene.h"  // relative: installed with the public API

namespace phongcl {

enum class ShadowMode {
  automatic,  // geometry when the scene has objects, else screen
  screen,     // march across the G-buffer's depth: any renderer's G-buffer, no scene geometry needed
  geometry,   // trace the scene's objects (exact)
  off,        // ignore the lights' "shadows"
};

std::string to_string(ShadowMode mode);
// "auto", "screen", "geometry", "off"; throws std::invalid_argument listing them otherwise.
ShadowMode parse_shadow_mode(const std::string& name);

struct ShadowSettings {
  ShadowMode mode = ShadowMode::automatic;
  int steps = 32;            // screen: samples along each ray, 1 to 1024
  double thickness = -0.06;  // screen: > 0 world units; < 0 that fraction of the surface's depth
  int rays = 64;             // geometry: rays per pixel over an area light without its own "shadow_rays",
                             // 1 to kMaxShadowRays (1: one ray to the centre, a hard shadow)
  int environment_rays = 64; // visibility rays per pixel of an environment light without its own "rays",
                             // 1 to kMaxEnvironmentRays (docs/environment.md "Visibility": error against time)
  bool operator==(const ShadowSettings&) const = default;
};

// The thickness as a user writes it: "0.25" (world units) or "6%" (of the surface's depth).
// Throws std::invalid_argument for anything else, zero, or a negative or non-finite number.
double parse_shadow_thickness(const std::string& text);
std::string format_shadow_thickness(double thickness);

// Throws std::invalid_argument naming the setting that is out of range.
void check_shadow_settings(const ShadowSettings& settings);

// The rays a light's shadow takes in geometry mode: its own "shadow_rays", else the settings'; 1
// (one ray, a hard shadow) for a point, spot or directional light without a size.
int shadow_rays(const AreaLight& light, const ShadowSettings& settings);
int shadow_rays(const Light& light, const ShadowSettings& settings);
// An environment light's visibility rays: its own "rays", else the settings' environment_rays.
int shadow_rays(const EnvironmentLight& light, const ShadowSettings& settings);

}  // namespace phongcl
