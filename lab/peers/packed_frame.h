#pragma once
// What the C++ peers shade: the G-buffer and scene packed once into float structure-of-arrays
// (positions relative to the eye, a material index per pixel, lights and materials in float).
// Packing is outside every timed region of the peers: it stands for the layout a renderer would
// hand over. (The OpenCL path's packing is in its end-to-end time, not its kernel time.)
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

namespace phongcl {

// 64-byte aligned storage: large mallocs sit 16 bytes into a page, which splits every AVX-512 load
// across two cache lines.
template <typename T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  CacheLineAllocator() = default;
  template <typename U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }
  template <typename U>
  bool operator==(const CacheLineAllocator<U>&) const { return true; }
};
template <typename T>
using AlignedVector = std::vector<T, CacheLineAllocator<T>>;

inline constexpr std::int32_t kPeerBackground = -1;
// Planes are padded to a multiple of this many pixels (zeros, background), so the SIMD peer's
// blocks always read whole registers.
inline constexpr std::size_t kPeerPadding = 16;

// Per pixel: 6 floats and one int32 read (28 bytes), RGBA float written (16 bytes).
struct PackedFrame {
  std::size_t pixels = 0;  // planes hold pixels rounded up to kPeerPadding
  AlignedVector<float> px, py, pz;  // position - eye, subtracted in double; 0 where not shaded
  AlignedVector<float> nx, ny, nz;  // normal, any length; 0 where not shaded
  AlignedVector<std::int32_t> material;  // index into PackedScene's tables, kPeerBackground if not shaded
};

// Lights and materials as structure of arrays, so a SIMD lane per pixel gathers its material and
// every lane reads the same light (a broadcast).
struct PackedScene {
  // Material tables, entry 0 first: the background as a material (ambient = background colour,
  // kd = ks = 0, alpha 0), so material index -1 reads it at table + 1 - 1 and the peers need no
  // branch for background pixels (their zero P and N give zero light sums). ambient is ka * La.
  std::vector<float> ambient_r, ambient_g, ambient_b, kd_r, kd_g, kd_b, ks_r, ks_g, ks_b, shininess, alpha;
  // Point lights: position - eye; directional lights: l = -normalize(direction), both in double first.
  std::vector<float> point_x, point_y, point_z, point_r, point_g, point_b;  // point and spot lights
  // Their shapes (docs/shading.md "The formula"), read by cpp-tiled only: 1/d^k power, 1/R (0: no
  // range), the spot's unit axis and 1 - cos(A/2), 1 - cos(A/2 + P), 1/(the two's difference)
  // (points: versines 3, every direction inside); and a bounding sphere (radius < 0: reaches everything).
  std::vector<float> falloff_power, inverse_range, axis_x, axis_y, axis_z, versine_inner, versine_outer, inverse_cone_width;
  std::vector<float> bound_x, bound_y, bound_z, bound_radius;
  bool linking = false;  // some light lights only some materials: no peer implements that
  std::vector<float> dir_x, dir_y, dir_z, dir_r, dir_g, dir_b;

  int point_count() const { return static_cast<int>(point_x.size()); }
  int directional_count() const { return static_cast<int>(dir_x.size()); }
};

// Throws InputError for material indices out of range and for per-pixel material channels, which
// the peers do not implement (they shade from the material table, as the benchmark scenes do).
PackedFrame pack_frame(const GBuffer& gbuffer, const Scene& scene);
// Spots are packed with the point lights; cpp-scalar and cpp-simd shade unshaped lights only
// (no falloff, range, cone or linking), cpp-tiled all but linking.
PackedScene pack_scene(const Scene& scene);

}  // namespace phongcl
