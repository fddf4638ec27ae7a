#pragma once
// The C++ peers the OpenCL kernel is measured against (bench --throughput): the same formula in float on the
// same packed input (peers/packed_frame.h), written to `rgba` (4 floats per pixel, as the kernel does).
#include <string>

#include "peers/packed_frame.h"

namespace phongcl {

// cpp-scalar: one thread, a plain loop over pixels, -O3 -march=native; the baseline every speed-up
// is quoted against.
void shade_scalar(const PackedFrame& frame, const PackedScene& scene, float* rgba);

// cpp-simd: every core (OpenMP), each thread's pixels vectorised (`omp simd`, AVX-512 here).
void shade_simd(const PackedFrame& frame, const PackedScene& scene, float* rgba);

// cpp-tiled: tiled light culling (ISPC's examples/cpu/deferred) on every core, each tile row
// vectorised: per tile_size x tile_size tile the lights whose bounds reach its shaded positions,
// then its pixels from that list (falloff, range window and spot cones; no light linking).
struct TiledPeerStats {
  double culling_ms = 0.0, shading_ms = 0.0;  // wall clock of the two passes
  double kept_pairs = 0.0;                     // shaded pixel-light pairs the culling kept
};
// Its schedule: the defaults are the best of bench --many-lights --peer-schedules on scenes/large.
struct TiledPeerSchedule {
  int tile_size = 16;      // pixels per side of a culling tile
  int coarse_tiles = 8;    // tiles per side of the first culling level's boxes
  int tiles_per_task = 16;  // tiles a thread takes at a time while shading (OpenMP's dynamic chunk)
  bool operator==(const TiledPeerSchedule&) const = default;
};
// e.g. "tiles 16, coarse 8, 16 tiles/task"
std::string describe(TiledPeerSchedule schedule);
TiledPeerStats shade_tiled(const PackedFrame& frame, const PackedScene& scene, int width, int height,
                           TiledPeerSchedule schedule, float* rgba);

}  // namespace phongcl
