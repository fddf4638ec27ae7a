#pragma once
// The accuracy the product promises (docs/shading.md "Accuracy"), defined once. Every
// implementation of the formula (the kernel in every variant but half-storage, the C++ and Halide
// peers) against the double-precision reference, on every shaded pixel's R, G and B:
//
//     |got - want| <= kRelativeBound * max(|want|, kErrorFloor)
//
// that is, 5e-4 relative, and 5e-10 absolute where |want| is below 1e-6. shading_error's max_rel
// is the largest |got - want| / max(|want|, kErrorFloor), as `phongcl compare` measures it with its
// default floor, so a test holds it to kRelativeBound. python/tests/accuracy_bound.py reads both
// numbers from this file.
//
// Why float meets it: each shaded value is a short chain of float operations (normalise: ~3 ulp;
// dot products: ~2 ulp; the light sum: n ulp for n lights), each ulp 6e-8, so the diffuse part is
// good to ~1e-6. The specular x^q amplifies the error of x by q; the kernel takes log(x) from
// 1 - v.r = |v - r|^2/2 without cancellation, leaving an exponent error of about
// q * |v - r| * 2e-7, under 1e-4 where the highlight is still visible (q * |v - r|^2 < ~20) for
// q <= 1000. 5e-4 leaves a factor of 5 for the worst of thousands of pixels. The floor is there so
// that a value of 0 (a black material, a light that misses) has a defined ratio; it is far below
// anything a display or a half-float file resolves.
#include <vector>

#include "image/image.h"

namespace phongcl::testing {

constexpr double kRelativeBound = 5e-4;
constexpr double kErrorFloor = 1e-6;

// The error of `got` against `want` over `mask` (every pixel if empty), measured as the bound is
// stated; a test holds max_rel to kRelativeBound, or to a tighter bound it justifies.
inline ErrorStats shading_error(const Image& got, const Image& want, const std::vector<bool>& mask = {}) {
  return compare_images(got, want, kErrorFloor, mask);
}

}  // namespace phongcl::testing
