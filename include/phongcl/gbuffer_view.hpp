#pragma once
// A G-buffer in the caller's memory: planes or interleaved arrays, any strides (a NumPy array's,
// an image library's rows). make_gbuffer() reads it once into phongcl's planar GBuffer, which a
// Relighter then packs into device memory; the caller's memory is not used afterwards.
#include <cstddef>

#include "gbuffer/gbuffer.h"  // installed beside this header

namespace phongcl {

// One float channel: pixel (x, y) is data[y * row_stride + x * pixel_stride], strides in floats
// (negative ones allowed). An empty view (data null) is an absent channel.
struct ChannelView {
  const float* data = nullptr;
  std::ptrdiff_t pixel_stride = 1;
  std::ptrdiff_t row_stride = 0;  // 0: width * pixel_stride (rows packed)
};

struct Vec3View {
  ChannelView x, y, z;
};
// x y z interleaved per pixel, rows packed: an (H, W, 3) array.
inline Vec3View interleaved3(const float* xyz) { return {{xyz, 3}, {xyz + 1, 3}, {xyz + 2, 3}}; }
// Three planes of width * height values each.
inline Vec3View planar3(const float* x, const float* y, const float* z) { return {{x}, {y}, {z}}; }

struct GBufferView {
  int width = 0, height = 0;
  Vec3View position, normal;  // P and N (any length), required
  ChannelView material;       // index into the scene's materials as a float, negative = background; required
  ChannelView alpha;          // optional: 0 marks background, as renderers write it
  Vec3View ka, kd, ks;        // optional per-pixel materials; each complete group overrides the table
  ChannelView shininess;      // optional
};

// Throws std::invalid_argument for a size below 1, a missing P, N or material, or a per-pixel group
// with only some of its channels.
GBuffer make_gbuffer(const GBufferView& view);

}  // namespace phongcl
