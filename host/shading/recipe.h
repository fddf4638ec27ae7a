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

namespace phongcl {

struct ShadeOptions {
  Precision precision = Precision::precise;
  bool specialise = true;           // false: the general kernel, everything compiled in
  std::size_t max_tile_pixels = 0;  // 0: as large as the device allows
  bool write_terms = false;         // also return ambient, diffuse and specular separately (AOVs)
  int lanes = 0;                    // pixels per work-item: 1, 2, 4, 8 or 16; 0: the device's choice
  Culling culling = Culling::automatic;
  int tile_size = 16;               // culling tiles of tile_size x tile_size pixels
};

struct Recipe {
  Precision precision = Precision::precise;
  bool specialised = true;
  int point_lights = 0, directional_lights = 0;  // point_lights counts spots too (one array)
  int spot_lights = 0;
  bool point_count_in_code = false, directional_count_in_code = false;  // compile-time, loops unroll
  bool point_code = true, directional_code = true;                      // light types compiled in
  // Light shapes (kernels/light_shape.h), each compiled in only when some light has it.
  int falloff_power = 0;       // every point and spot light's 1/d^k power (0: no falloff)
  bool falloff_mixed = false;  // powers differ: each light's is read
  bool range_window = false, spot_code = false;
  int link_words = 0;          // light linking: mask words per light; 0: every light lights every material
  bool tiled = false;          // tiled light culling (host/shading/tile_culling.h)
  int tile_size = 16;
  bool specular = true, ambient = true;
  bool single_material = false;  // no per-pixel material fetch
  bool material_selects = false;  // table of <= lanes materials: per-lane selects, no gather
  int material_count = 0;
  bool per_pixel_ka = false, per_pixel_kd = false, per_pixel_ks = false, per_pixel_shininess = false;
  bool uniforms_in_constant = false;  // lights and materials in __constant memory
  bool write_terms = false;
  int lanes = 1;                      // pixels per work-item (explicit SIMD on CPU devices)
  std::vector<std::string> reasons;   // one line per decision, for --explain

  int plane_count() const;  // G-buffer planes the device buffer holds
  std::string build_options() const;
  std::string summary() const;  // one line: "precise, specialised: 2 point (unrolled) + 1 directional, ..."
};

// Lights up to this many of a type become compile-time constants (kernels/layout.h).
inline constexpr int kUnrollLightLimit = PHONGCL_UNROLL_LIGHT_LIMIT;

// Throws std::runtime_error when the device cannot run the precision (double without fp64).
Recipe make_recipe(const Scene& scene, const GBuffer& gbuffer, const DeviceInfo& device, const ShadeOptions& options);

}  // namespace phongcl
