#pragma once
// What a scene needs from the kernel, derived from the scene and the G-buffer: light types, terms,
// material paths, precision. It becomes the kernel's build options; the rest is compiled out.
#include <string>
#include <vector>

#include "cl/device.h"
#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/device_layout.h"
#include "shading/precision.h"
#include "shading/shadow_settings.h"

namespace phongcl {

struct ShadeOptions {
  Precision precision = Precision::precise;
  bool specialise = true;           // false: the general kernel, everything compiled in
  std::size_t max_tile_pixels = 0;  // 0: as large as the device allows
  bool write_terms = false;         // also return ambient, diffuse and specular separately (AOVs)
  int lanes = 0;                    // pixels per work-item: 1, 2, 4, 8 or 16; 0: the device's choice
  Culling culling = Culling::automatic;
  int tile_size = 16;               // culling tiles of tile_size pixels, lists per half tile (tile_culling.h)
  ShadowSettings shadows{};         // how lights with "shadows": true cast them (docs/shadows.md)
};

// One row of the recipe: a flag of kernels/features.h, the value the kernel is built with, and why.
struct RecipeFlag {
  std::string name;     // "SPECULAR"
  std::string value;    // "1" or "0"; a count; "__constant"
  std::string why;      // one line for --explain, topic first: "specular: compiled in (some material has ks > 0)"
  std::string summary;  // its words in the one-line summary ("specular"), or empty
};

// What the kernel is built with. `flags` is the one table: the build options, --explain's reasons
// and the summary line are its renderings. The typed fields are the decisions the host acts on.
struct Recipe {
  Precision precision = Precision::precise;
  bool specialised = true;
  int point_lights = 0, directional_lights = 0;  // point_lights counts spots too (one array)
  int spot_lights = 0;
  int area_lights = 0;   // rects and disks (their own table, untiled)
  bool environment = false;          // the scene's environment light
  bool environment_shadows = false;  // its visibility: rays traced (geometry) or horizons (screen)
  int environment_rays = 0;          // rays per pixel with environment_shadows
  int link_words = 0;    // light linking: mask words per light; 0: every light lights every material
  bool tiled = false;    // tiled light culling (host/shading/tile_culling.h)
  int tile_size = 16;
  bool per_pixel_ka = false, per_pixel_kd = false, per_pixel_ks = false, per_pixel_shininess = false;
  bool position_rest = false;  // positions and point lights as float pairs: three rest planes after the others
  bool write_terms = false;
  int lanes = 1;         // pixels per work-item (explicit SIMD on CPU devices)
  ShadowMode shadows = ShadowMode::off;  // geometry, screen or off (no light casts shadows, or off as asked)
  ShadowSettings shadow_settings;        // the screen-space march's steps and thickness
  int shadow_casters = 0;                // lights that cast shadows
  std::vector<std::string> light_groups; // the groups whose layers the kernel writes (with write_terms)
  std::vector<RecipeFlag> flags;

  int plane_count() const;  // G-buffer planes the device buffer holds
  // The flag's value; throws std::out_of_range for a name that is not in the table.
  const std::string& value(const std::string& name) const;
  std::string build_options() const;          // "-cl-std=CL1.2 -DPHONGCL_LANES=16 ..."
  std::vector<std::string> reasons() const;   // one line per flag: why, and the define
  std::string summary() const;  // one line: "precise, specialised: 2 point (unrolled), 1 directional (unrolled), ..."
};

// Lights up to this many of a type become compile-time constants (kernels/layout.h).
inline constexpr int kUnrollLightLimit = PHONGCL_UNROLL_LIGHT_LIMIT;

// Throws std::runtime_error when the device cannot run the precision (double without fp64).
Recipe make_recipe(const Scene& scene, const GBuffer& gbuffer, const DeviceInfo& device, const ShadeOptions& options);

}  // namespace phongcl
