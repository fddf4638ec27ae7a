#pragma once
// The per-pixel loops of display transforms (color/display.h, color/view_pipeline.h), on blocks
// of pixels held as three planes (r, g, b): the scalar ones every x86-64 runs, and AVX2 ones (eight
// pixels a step, table lookups as gathers) chosen at run time where the CPU has AVX2 and FMA. The
// two agree but for the rounding of fused multiply-adds (the tests hold them to each other).
#include <cstddef>
#include <cstdint>

namespace phongcl {

struct PixelKernels {
  // Premultiplied RGBA pixels into exposed planes: (rgb + (1 - alpha) * background) * scale, with
  // colour where alpha <= 0 left out, alpha clamped to [0, 1] (NaN: 0), NaN colour as 0, and
  // the result clamped to +-FLT_MAX.
  void (*flatten)(const float* rgba, std::size_t n, const float background[3], float scale, float* const planes[3]);
  // Each plane through its table: bucket bits >> 16 of the float, linear in the low 16 bits.
  void (*separable)(const float* const tables[3], float* const planes[3], std::size_t n);
  // A 3D LUT over [0, 1]^3 (inputs clamped, NaN as 0), data[((b * size + g) * size + r) * 3 + c],
  // followed by one float of padding (the AVX2 loop loads a node's RGB as four floats).
  void (*lut3d)(const float* data, int size, bool tetrahedral, float* const planes[3], std::size_t n);
  void (*matrix)(const float m[3][3], const float offset[3], float* const planes[3], std::size_t n);
  // Display values into RGBA bytes, alpha 255: round half up (as Blender), clamped, NaN as 0.
  void (*to_bytes)(const float* const planes[3], std::size_t n, std::uint8_t* rgba);
};

const PixelKernels& scalar_pixel_kernels();
const PixelKernels* avx2_pixel_kernels();  // nullptr where this CPU lacks AVX2 or FMA
const PixelKernels& best_pixel_kernels();

}  // namespace phongcl
