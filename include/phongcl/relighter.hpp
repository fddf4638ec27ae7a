#pragma once
// phongcl::Relighter: a G-buffer packed once into an OpenCL device's memory and shaded again after
// each change of lights, materials or eye. A re-shade uploads only what changed (the light and
// material tables are a few hundred bytes; the G-buffer only after an eye move) and costs the kernel
// and the download; the kernel is rebuilt only when the recipe changes (say, the number of lights),
// and built programs are cached in memory and on disk.
//
// The room headers included here are installed beside this one (include/phongcl/<room>/).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cl/device_info.h"
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "scene/scene.h"
#include "shading/precision.h"

namespace phongcl {

struct RelighterOptions {
  std::string device;                        // as `phongcl shade --device`: index or name; empty: first CPU device
  Precision precision = Precision::precise;  // README "Precision variants"
  bool specialise = true;                    // false: the general kernel
  int lanes = 0;                             // pixels per work-item (1, 2, 4, 8, 16); 0: the device's choice
};

// What the last shade() cost, in milliseconds. build: compiling or loading the kernel (0 unless the
// recipe changed); pack: packing what changed on the host; upload: handing it to the device; kernel:
// from profiling events; download: mapping the output and copying it into the image; total: wall
// clock of all of it.
struct RelightTimings {
  double build_ms = 0.0, pack_ms = 0.0, upload_ms = 0.0, kernel_ms = 0.0, download_ms = 0.0, total_ms = 0.0;
  bool rebuilt = false;           // the recipe changed, so the kernel was (re)built or fetched from the cache
  bool gbuffer_uploaded = false;  // the G-buffer was packed and uploaded (the first frame, or a new eye)
};

class Relighter {
 public:
  // Picks the device, checks the scene's materials against the G-buffer's indices (InputError),
  // builds the kernel and packs the G-buffer into device memory. The G-buffer is copied (or moved):
  // an eye change re-packs positions from it.
  Relighter(const Scene& scene, const GBuffer& gbuffer, const RelighterOptions& options = {});
  Relighter(const Scene& scene, GBuffer&& gbuffer, const RelighterOptions& options = {});
  ~Relighter();
  Relighter(Relighter&&) noexcept;
  Relighter& operator=(Relighter&&) noexcept;

  // Each takes effect at the next shade(). std::invalid_argument for non-finite values, negative
  // colours or shininess, a zero direction; InputError when the G-buffer uses a material index
  // the new table lacks (the previous state is kept on either).
  void set_lights(const std::vector<Light>& lights);
  void set_materials(const std::vector<Material>& materials);
  void set_camera_eye(const glm::dvec3& eye);

  // RGBA float, width() x height(), with the G-buffer's data and display windows.
  Image shade();
  // The same into a caller's buffer of 4 * width() * height() floats, interleaved RGBA, row-major
  // (std::invalid_argument if `floats` differs). Safe to call from several threads: calls take turns.
  void shade_into(float* rgba, std::size_t floats);

  int width() const;
  int height() const;
  const Scene& scene() const;  // with the lights, materials and eye set so far
  const DeviceInfo& device() const;
  std::string kernel_summary() const;  // the recipe in one line, as `phongcl shade` prints it
  std::string build_options() const;
  RelightTimings last_timings() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Every OpenCL device of every platform, numbered as RelighterOptions::device counts them.
std::vector<DeviceInfo> available_devices();

}  // namespace phongcl
