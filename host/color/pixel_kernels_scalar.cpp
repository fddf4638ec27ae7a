// The per-pixel loops in plain C++ (color/pixel_kernels.h): the reference for the AVX2 ones, and
// what CPUs without AVX2 run.
#include <algorithm>
#include <cmath>
#include <limits>

#include "color/display_math.h"
#include "color/pixel_kernels.h"

namespace phongcl {

namespace {

constexpr float kFloatMax = std::numeric_limits<float>::max();

void flatten(const float* rgba, std::size_t n, const float background[3], float scale, float* const planes[3]) {
  for (std::size_t i = 0; i < n; ++i) {
    const float* pixel = rgba + 4 * i;
    const float alpha = pixel[3] > 0.0f ? std::min(pixel[3], 1.0f) : 0.0f;  // NaN -> 0
    for (int c = 0; c < 3; ++c) {
      const float color = alpha > 0.0f && pixel[c] == pixel[c] ? pixel[c] : 0.0f;
      planes[c][i] = std::clamp((color + (1.0f - alpha) * background[c]) * scale, -kFloatMax, kFloatMax);
    }
  }
}

void separable(const float* const tables[3], float* const planes[3], std::size_t n) {
  for (int c = 0; c < 3; ++c) {
    const float* table = tables[c];
    float* plane = planes[c];
    for (std::size_t i = 0; i < n; ++i) plane[i] = table_lookup(table, plane[i]);
  }
}

float grid_coordinate(float v, int size) {
  const float clamped = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;  // NaN -> 0
  return clamped * static_cast<float>(size - 1);
}

// OpenColorIO's tetrahedral and trilinear interpolation (Lut3DOpCPU.cpp), on the same grid.
void lut3d(const float* data, int size, bool tetrahedral, float* const planes[3], std::size_t n) {
  const std::size_t step_r = 3, step_g = 3 * static_cast<std::size_t>(size), step_b = step_g * size;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = grid_coordinate(planes[0][i], size), y = grid_coordinate(planes[1][i], size),
                z = grid_coordinate(planes[2][i], size);
    const int x0 = std::min(static_cast<int>(x), size - 2), y0 = std::min(static_cast<int>(y), size - 2),
              z0 = std::min(static_cast<int>(z), size - 2);
    const float fx = x - x0, fy = y - y0, fz = z - z0;
    const float* n000 = data + x0 * step_r + y0 * step_g + z0 * step_b;
    const float* n100 = n000 + step_r;
    const float* n010 = n000 + step_g;
    const float* n001 = n000 + step_b;
    const float* n110 = n100 + step_g;
    const float* n101 = n100 + step_b;
    const float* n011 = n010 + step_b;
    const float* n111 = n110 + step_b;
    float out[3];
    if (!tetrahedral) {
      for (int c = 0; c < 3; ++c) {
        const float a = n000[c] + fx * (n100[c] - n000[c]), b = n010[c] + fx * (n110[c] - n010[c]);
        const float d = n001[c] + fx * (n101[c] - n001[c]), e = n011[c] + fx * (n111[c] - n011[c]);
        const float f = a + fy * (b - a), g = d + fy * (e - d);
        out[c] = f + fz * (g - f);
      }
    } else {
      // The tetrahedron of the cube that holds the point: the order of its three fractions.
      const float *corner1, *corner2;
      float w0, w1, w2, w3;
      if (fx > fy) {
        if (fy > fz) corner1 = n100, corner2 = n110, w0 = 1 - fx, w1 = fx - fy, w2 = fy - fz, w3 = fz;
        else if (fx > fz) corner1 = n100, corner2 = n101, w0 = 1 - fx, w1 = fx - fz, w2 = fz - fy, w3 = fy;
        else corner1 = n001, corner2 = n101, w0 = 1 - fz, w1 = fz - fx, w2 = fx - fy, w3 = fy;
      } else {
        if (fz > fy) corner1 = n001, corner2 = n011, w0 = 1 - fz, w1 = fz - fy, w2 = fy - fx, w3 = fx;
        else if (fz > fx) corner1 = n010, corner2 = n011, w0 = 1 - fy, w1 = fy - fz, w2 = fz - fx, w3 = fx;
        else corner1 = n010, corner2 = n110, w0 = 1 - fy, w1 = fy - fx, w2 = fx - fz, w3 = fz;
      }
      for (int c = 0; c < 3; ++c) out[c] = w0 * n000[c] + w1 * corner1[c] + w2 * corner2[c] + w3 * n111[c];
    }
    for (int c = 0; c < 3; ++c) planes[c][i] = out[c];
  }
}

void matrix(const float m[3][3], const float offset[3], float* const planes[3], std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const float r = planes[0][i], g = planes[1][i], b = planes[2][i];
    for (int c = 0; c < 3; ++c) planes[c][i] = m[c][0] * r + m[c][1] * g + m[c][2] * b + offset[c];
  }
}

void to_bytes(const float* const planes[3], std::size_t n, std::uint8_t* rgba) {
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = display_byte(planes[c][i]);
    rgba[4 * i + 3] = 255;
  }
}

}  // namespace

const PixelKernels& scalar_pixel_kernels() {
  static const PixelKernels kernels{flatten, separable, lut3d, matrix, to_bytes};
  return kernels;
}

const PixelKernels& best_pixel_kernels() {
  static const PixelKernels& best = avx2_pixel_kernels() ? *avx2_pixel_kernels() : scalar_pixel_kernels();
  return best;
}

}  // namespace phongcl
