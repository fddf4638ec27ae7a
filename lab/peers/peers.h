#pragma once
// The C++ peers the OpenCL kernel is measured against (issue 5): the same formula in float on the
// same packed input (peers/packed_frame.h), written to `rgba` (4 floats per pixel, as the kernel does).
#include "peers/packed_frame.h"

namespace phongcl {

// cpp-scalar: one thread, a plain loop over pixels, -O3 -march=native; the baseline every speed-up
// is quoted against.
void shade_scalar(const PackedFrame& frame, const PackedScene& scene, float* rgba);

// cpp-simd: every core (OpenMP), each thread's pixels vectorised (`omp simd`, AVX-512 here).
void shade_simd(const PackedFrame& frame, const PackedScene& scene, float* rgba);

}  // namespace phongcl
