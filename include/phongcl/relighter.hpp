#pragma once
// phongcl::Relighter: a G-buffer packed once into an OpenCL device's memory and shaded again after
// each change of lights, materials or eye. A re-shade uploads only what changed (the light and
// material tables are a few hundred bytes; the G-buffer only after an eye move) and costs the kernel
// and the download; the kernel is rebuilt only when the recipe changes (say, the number of lights),
// and built programs are cached in memory and on disk. A frame larger than the device's largest
// allocation is shaded in tiles, re-packed each time. `phongcl shade` is a user of this class and
// prints what last_report() says.
//
// The room headers included here are installed beside this one (include/phongcl/<room>/).
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cl/device_info.h"
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "scene/scene.h"
#include "shading/precision.h"
#include "shading/shade_stats.h"
#include "shading/shadow_settings.h"

namespace phongcl {

struct RelighterOptions {
  std::string device;                        // as `phongcl shade --device`: index or name; empty: its default
  Precision precision = Precision::precise;  // docs/shading.md "Precision variants"
  bool specialise = true;                    // false: the general kernel
  int lanes = 0;                             // pixels per work-item (1, 2, 4, 8, 16); 0: the device's choice
  Culling culling = Culling::automatic;      // docs/performance.md "Tiled light culling"
  int tile_size = 16;                        // culling tiles of tile_size pixels (docs/performance.md)
  bool terms = false;                        // also shade ambient, diffuse and specular apart: shade(TermImages&)
  std::size_t max_tile_pixels = 0;           // > 0: at most this many pixels per launch (else the device's limit)
  ShadowSettings shadows{};                  // how lights with "shadows": true cast them (docs/shadows.md)
};

// Throws std::invalid_argument naming the option for a value no device takes: lanes other than 0,
// 1, 2, 4, 8 or 16; tile_size outside [1, 1024]; shadow steps or thickness out of range. The
// Relighter checks its options with it, and front ends call it before reading any input, so every
// one refuses the same values alike.
void check_options(const RelighterOptions& options);

class Relighter {
 public:
  // Picks the device and takes the frame (set_frame). The G-buffer is copied (or moved): an eye
  // change re-packs positions from it.
  Relighter(const Scene& scene, const GBuffer& gbuffer, const RelighterOptions& options = {});
  Relighter(const Scene& scene, GBuffer&& gbuffer, const RelighterOptions& options = {});
  // Picks the device only (std::runtime_error naming an unknown one); set_frame() before shade().
  explicit Relighter(const RelighterOptions& options);
  ~Relighter();
  Relighter(Relighter&&) noexcept;
  Relighter& operator=(Relighter&&) noexcept;

  // A new scene and G-buffer (the next frame of a sequence), keeping the device, the built kernels
  // and the device buffers. InputError when the G-buffer uses a material index the scene lacks;
  // std::runtime_error when the device cannot run the precision, or when the frame would need more
  // memory than the machine has available or the address-space limit leaves (naming the largest
  // need; set_lights and set_materials check the same). The previous frame is kept on each.
  void set_frame(const Scene& scene, GBuffer&& gbuffer);

  // Each takes effect at the next shade(). std::invalid_argument for non-finite values, negative
  // colours or shininess, a zero direction; InputError when the G-buffer uses a material index
  // the new table lacks (the previous state is kept on either).
  void set_lights(const std::vector<Light>& lights);
  void set_area_lights(const std::vector<AreaLight>& lights);
  // The world's light (at most one); std::nullopt removes it. A changed rotation or strength keeps
  // the kernel and the map's irradiance (cached per file), and re-packs its one record.
  void set_environment(const std::optional<EnvironmentLight>& environment);
  void set_materials(const std::vector<Material>& materials);
  void set_camera_eye(const glm::dvec3& eye);

  // RGBA float, width() x height(), with the G-buffer's data and display windows. Frames larger
  // than the device's largest allocation are shaded in tiles (and re-packed for every shade).
  // std::logic_error without a frame.
  Image shade();
  // The same, and the three terms of the shading (AOVs) into `terms`, with the scene's light groups'
  // images (each group's diffuse + specular; terms.group_names says which); needs
  // RelighterOptions::terms (std::logic_error otherwise).
  Image shade(TermImages& terms);
  // The same into a caller's buffer of 4 * width() * height() floats, interleaved RGBA, row-major
  // (std::invalid_argument if `floats` differs). Safe to call from several threads: calls take turns.
  void shade_into(float* rgba, std::size_t floats);

  int width() const;   // 0 without a frame
  int height() const;
  const Scene& scene() const;  // with the lights, materials and eye set so far (std::logic_error without a frame)
  const GBuffer& gbuffer() const;
  const DeviceInfo& device() const;
  std::string kernel_summary() const;  // the recipe in one line, as `phongcl shade` prints it
  std::string build_options() const;
  // What the last shade() cost and found: timings, pixel counts, culling, tiles, the recipe and
  // why (`phongcl shade --explain`), warnings. Empty before the first shade().
  ShadeReport last_report() const;
  ShadeTimings last_timings() const;  // last_report().timings

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Every OpenCL device of every platform, numbered as RelighterOptions::device counts them.
std::vector<DeviceInfo> available_devices();

}  // namespace phongcl
