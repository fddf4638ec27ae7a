#pragma once
// RGB primaries as CIE xy chromaticities (OpenEXR's `chromaticities` attribute), and the linear
// RGB-to-XYZ matrix they define.
#include <array>

#include "exr/pixel_window.h"  // Chromaticities

namespace phongcl {

using Matrix3 = std::array<std::array<double, 3>, 3>;  // row-major: out[i] = sum_j m[i][j] * in[j]

// ITU-R BT.709 / sRGB primaries, D65 white.
inline constexpr Chromaticities kRec709Chromaticities{{0.64f, 0.33f}, {0.30f, 0.60f}, {0.15f, 0.06f}, {0.3127f, 0.3290f}};

// The matrix taking linear RGB with these primaries to XYZ, scaled so that RGB (1, 1, 1) is the
// white point with Y = 1.
Matrix3 rgb_to_xyz(const Chromaticities& c);
Matrix3 inverse(const Matrix3& m);

// The primaries and white of a linear RGB space given its RGB-to-XYZ matrix (the inverse of
// rgb_to_xyz, up to the white's luminance).
Chromaticities chromaticities_of(const Matrix3& rgb_to_xyz);

}  // namespace phongcl
