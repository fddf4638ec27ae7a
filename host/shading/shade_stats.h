#pragma once
// What one shaded frame cost and found: timings, pixel classes, culling, the kernel's recipe. The
// Relighter returns it (include/phongcl/relighter.hpp) and `phongcl shade` prints it.
#include <cstddef>
#include <string>
#include <vector>

// Relative: this header is installed with the public API (include/phongcl/), beside its rooms.
#include "../cl/cache_outcome.h"
#include "../gbuffer/gbuffer.h"  // PixelClass
#include "../image/image.h"

namespace phongcl {

// Milliseconds. build: compiling or loading the kernel (0 when the previous frame's is reused);
// pack: packing the G-buffer on the host (0 when it is still resident); upload: handing it and the
// light and material tables to the device; kernel: profiling events, culling included; download:
// mapping the output and copying it into the image; total: wall clock of the frame, build excluded.
struct ShadeTimings {
  double build_ms = 0.0, pack_ms = 0.0, upload_ms = 0.0, kernel_ms = 0.0, download_ms = 0.0, total_ms = 0.0;
  bool rebuilt = false;           // the recipe changed, so the kernel was (re)built or fetched from the cache
  bool gbuffer_uploaded = false;  // the G-buffer was packed and uploaded (the first frame, a new eye, or tiles)
};

// How many pixels fell in each class: the non-finite ones are left unshaded.
struct PixelCounts {
  std::size_t shaded = 0, background = 0, nonfinite_position = 0, nonfinite_normal = 0, nonfinite_material = 0;
  void add(PixelClass pixel_class);
  PixelCounts& operator+=(const PixelCounts& other);
};

// What one frame's tiled light culling kept.
struct CullingStats {
  int tile_size = 0, tile_rows = 0;  // each list's tile: tile_size wide, tile_rows tall
  std::size_t tiles = 0, shaded_tiles = 0;  // shaded: tiles with at least one shaded pixel
  std::size_t max_lights_per_tile = 0;
  double list_entries = 0.0;                // sum over shaded tiles of their list lengths
  double holding_entries = 0.0;             // of them, the lights whose bounds hold all of their tile
  double kept_pairs = 0.0;                  // sum over shaded pixels of their tile's list length
  double culling_ms = 0.0;                  // the culling passes and their prefix sums
  double mean_lights_per_tile() const { return shaded_tiles ? list_entries / static_cast<double>(shaded_tiles) : 0.0; }
  double mean_holding_per_tile() const {
    return shaded_tiles ? holding_entries / static_cast<double>(shaded_tiles) : 0.0;
  }
  CullingStats& operator+=(const CullingStats& other);
};

// What one frame's tiled shadow culling found: per (tile, shadow-casting light) pair a list of
// candidates, or too many (the pair's rays traverse the BVH).
struct ShadowCullingStats {
  double culling_ms = 0.0;  // the passes' profiling events and the host's prefix sums
  std::size_t pairs = 0, entries = 0, traversing = 0;
  double candidates_per_pair() const { return pairs > traversing ? static_cast<double>(entries) / (pairs - traversing) : 0.0; }
  ShadowCullingStats& operator+=(const ShadowCullingStats& other);
};

// The three terms of L_o as images (RGB, alpha as in the combined image, premultiplied like it);
// their sum is the combined image up to float rounding.
struct TermImages {
  Image ambient, diffuse, specular;
  // With light groups: each group's diffuse + specular, premultiplied like the combined image, in
  // light_groups() order; ambient + every group + the ungrouped lights' light = the combined image.
  std::vector<std::string> group_names;
  std::vector<Image> groups;
};

struct ShadeReport {
  ShadeTimings timings;
  PixelCounts counts;
  bool culled = false;   // tiled light culling ran; then `culling` says what it kept
  CullingStats culling;  // its time is also inside timings.kernel_ms
  std::size_t tiles = 0;  // launches: more than 1 when the frame is larger than one device allocation
  CacheOutcome cache = CacheOutcome::memory_hit;  // memory_hit also when the previous frame's kernel is reused
  std::vector<std::string> warnings;  // one line each, e.g. values half-storage flushed to zero
  // The kernel's recipe: what was compiled in and out.
  std::string kernel_summary;               // one line: "precise, specialised: 2 point (unrolled) + ..."
  std::vector<std::string> recipe_reasons;  // one line per decision and why (`phongcl shade --explain`)
  std::string build_options;
  int point_lights = 0, spot_lights = 0, directional_lights = 0;  // point_lights counts the spots too
  int area_lights = 0;                                            // rects and disks
  // How shadows were made, one line ("geometry: 2 lights, a BVH of ..."); empty without shadows.
  std::string shadows;
  bool shadows_culled = false;          // tiled shadow culling ran; then `shadow_culling` says what it found
  ShadowCullingStats shadow_culling;    // its time is also inside timings.kernel_ms
  // The on-disk program cache: its directory (empty: none writable) and why it could not be used.
  std::string disk_cache_directory, disk_cache_problem;
};

}  // namespace phongcl
