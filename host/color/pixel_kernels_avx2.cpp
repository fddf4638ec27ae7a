// The per-pixel loops with AVX2 and FMA, eight pixels a step (color/pixel_kernels.h); the last
// n % 8 pixels go through the scalar loops. This file alone is compiled with -mavx2 -mfma and runs
// only where the CPU has both; it uses intrinsics and no inline library templates, so none of its
// AVX2 code can stand in for the rest of the program's.
#include <immintrin.h>

#include "color/pixel_kernels.h"

namespace phongcl {

namespace {

constexpr std::size_t kLanes = 8;

struct Tail {  // the planes from pixel `first` on
  float* planes[3];
  Tail(float* const all[3], std::size_t first) : planes{all[0] + first, all[1] + first, all[2] + first} {}
};

__m256 flatten_channel(__m256 color, __m256 alpha, __m256 background, __m256 scale) {
  const __m256 zero = _mm256_setzero_ps(), limit = _mm256_set1_ps(3.40282347e38f);
  // colour where alpha > 0 and the colour is a number
  const __m256 keep = _mm256_and_ps(_mm256_cmp_ps(alpha, zero, _CMP_GT_OQ), _mm256_cmp_ps(color, color, _CMP_ORD_Q));
  const __m256 under = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(1.0f), alpha), background);
  const __m256 value = _mm256_mul_ps(_mm256_add_ps(_mm256_and_ps(color, keep), under), scale);
  return _mm256_min_ps(_mm256_max_ps(value, _mm256_sub_ps(zero, limit)), limit);
}

void flatten(const float* rgba, std::size_t n, const float background[3], float scale, float* const planes[3]) {
  const __m256 scales = _mm256_set1_ps(scale);
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    // Eight RGBA pixels as four planes: pair pixels k and k + 4 in each register, then transpose
    // the 4x4 blocks of both 128-bit halves at once.
    const float* base = rgba + 4 * i;
    const __m256 a0 = _mm256_loadu_ps(base), a1 = _mm256_loadu_ps(base + 8), a2 = _mm256_loadu_ps(base + 16),
                 a3 = _mm256_loadu_ps(base + 24);
    const __m256 t0 = _mm256_permute2f128_ps(a0, a2, 0x20), t1 = _mm256_permute2f128_ps(a0, a2, 0x31);
    const __m256 t2 = _mm256_permute2f128_ps(a1, a3, 0x20), t3 = _mm256_permute2f128_ps(a1, a3, 0x31);
    const __m256 u0 = _mm256_unpacklo_ps(t0, t1), u1 = _mm256_unpackhi_ps(t0, t1);
    const __m256 u2 = _mm256_unpacklo_ps(t2, t3), u3 = _mm256_unpackhi_ps(t2, t3);
    const __m256 color[3] = {_mm256_shuffle_ps(u0, u2, 0x44), _mm256_shuffle_ps(u0, u2, 0xee), _mm256_shuffle_ps(u1, u3, 0x44)};
    // alpha in [0, 1], NaN -> 0 (max takes its second operand when the first is NaN)
    const __m256 alpha = _mm256_min_ps(_mm256_max_ps(_mm256_shuffle_ps(u1, u3, 0xee), _mm256_setzero_ps()), _mm256_set1_ps(1.0f));
    for (int c = 0; c < 3; ++c)
      _mm256_storeu_ps(planes[c] + i, flatten_channel(color[c], alpha, _mm256_set1_ps(background[c]), scales));
  }
  if (i < n) scalar_pixel_kernels().flatten(rgba + 4 * i, n - i, background, scale, Tail(planes, i).planes);
}

__m256 lookup(const float* table, __m256 value) {
  const __m256i bits = _mm256_castps_si256(value);
  const __m256i index = _mm256_srli_epi32(bits, 16);
  const __m256 fraction = _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_and_si256(bits, _mm256_set1_epi32(0xffff))),
                                        _mm256_set1_ps(1.0f / 65536.0f));
  const __m256 start = _mm256_i32gather_ps(table, index, 4);
  const __m256 end = _mm256_i32gather_ps(table + 1, index, 4);
  return _mm256_fmadd_ps(_mm256_sub_ps(end, start), fraction, start);
}

void separable(const float* const tables[3], float* const planes[3], std::size_t n) {
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes)
    for (int c = 0; c < 3; ++c) _mm256_storeu_ps(planes[c] + i, lookup(tables[c], _mm256_loadu_ps(planes[c] + i)));
  if (i < n) scalar_pixel_kernels().separable(tables, Tail(planes, i).planes, n - i);
}

__m256 grid_coordinate(__m256 v, __m256 last) {  // [0, 1] (NaN -> 0) times size - 1
  return _mm256_mul_ps(_mm256_min_ps(_mm256_max_ps(v, _mm256_setzero_ps()), _mm256_set1_ps(1.0f)), last);
}

__m256i select(__m256 mask, __m256i if_set, __m256i otherwise) {
  return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(otherwise), _mm256_castsi256_ps(if_set), mask));
}

__m256 gather(const float* data, __m256i index, int channel) { return _mm256_i32gather_ps(data + channel, index, 4); }

// The scalar loop's interpolation without its branches: the tetrahedron's second corner is the
// cube's origin stepped along the axis of the largest fraction, its third the far corner stepped
// back along the axis of the smallest; the weights are the sorted fractions' differences.
void lut3d(const float* data, int size, bool tetrahedral, float* const planes[3], std::size_t n) {
  const __m256 last = _mm256_set1_ps(static_cast<float>(size - 1));
  const __m256i highest_cell = _mm256_set1_epi32(size - 2);
  const int step_r = 3, step_g = 3 * size, step_b = 3 * size * size;
  const __m256i sr = _mm256_set1_epi32(step_r), sg = _mm256_set1_epi32(step_g), sb = _mm256_set1_epi32(step_b);
  const __m256i s_all = _mm256_set1_epi32(step_r + step_g + step_b);
  const __m256 one = _mm256_set1_ps(1.0f);
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    const __m256 x = grid_coordinate(_mm256_loadu_ps(planes[0] + i), last);
    const __m256 y = grid_coordinate(_mm256_loadu_ps(planes[1] + i), last);
    const __m256 z = grid_coordinate(_mm256_loadu_ps(planes[2] + i), last);
    const __m256i x0 = _mm256_min_epi32(_mm256_cvttps_epi32(x), highest_cell);
    const __m256i y0 = _mm256_min_epi32(_mm256_cvttps_epi32(y), highest_cell);
    const __m256i z0 = _mm256_min_epi32(_mm256_cvttps_epi32(z), highest_cell);
    const __m256 fx = _mm256_sub_ps(x, _mm256_cvtepi32_ps(x0));
    const __m256 fy = _mm256_sub_ps(y, _mm256_cvtepi32_ps(y0));
    const __m256 fz = _mm256_sub_ps(z, _mm256_cvtepi32_ps(z0));
    const __m256i origin = _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(x0, sr), _mm256_mullo_epi32(y0, sg)),
                                            _mm256_mullo_epi32(z0, sb));
    __m256 out[3];
    if (tetrahedral) {
      const __m256 xy = _mm256_cmp_ps(fx, fy, _CMP_GT_OQ), yz = _mm256_cmp_ps(fy, fz, _CMP_GT_OQ),
                   xz = _mm256_cmp_ps(fx, fz, _CMP_GT_OQ);
      // largest: x if x > y and x > z, y if y >= x and y > z, else z; smallest: x if y >= x and
      // z >= x, y if x > y and z >= y, else z (never the largest's axis unless all are equal,
      // where the weights of both corners are 0)
      const __m256i largest = select(_mm256_and_ps(xy, xz), sr, select(_mm256_andnot_ps(xy, yz), sg, sb));
      const __m256i smallest =
          select(_mm256_andnot_ps(_mm256_or_ps(xy, xz), _mm256_castsi256_ps(_mm256_set1_epi32(-1))), sr,
                 select(_mm256_andnot_ps(yz, xy), sg, sb));
      const __m256i corner1 = _mm256_add_epi32(origin, largest);
      const __m256i corner2 = _mm256_sub_epi32(_mm256_add_epi32(origin, s_all), smallest);
      const __m256i corner3 = _mm256_add_epi32(origin, s_all);
      const __m256 f_max = _mm256_max_ps(fx, _mm256_max_ps(fy, fz)), f_min = _mm256_min_ps(fx, _mm256_min_ps(fy, fz));
      const __m256 f_mid = _mm256_max_ps(_mm256_min_ps(fx, fy), _mm256_min_ps(_mm256_max_ps(fx, fy), fz));
      const __m256 w0 = _mm256_sub_ps(one, f_max), w1 = _mm256_sub_ps(f_max, f_mid), w2 = _mm256_sub_ps(f_mid, f_min);
      for (int c = 0; c < 3; ++c) {
        __m256 v = _mm256_mul_ps(w0, gather(data, origin, c));
        v = _mm256_fmadd_ps(w1, gather(data, corner1, c), v);
        v = _mm256_fmadd_ps(w2, gather(data, corner2, c), v);
        out[c] = _mm256_fmadd_ps(f_min, gather(data, corner3, c), v);
      }
    } else {
      const __m256i n100 = _mm256_add_epi32(origin, sr), n010 = _mm256_add_epi32(origin, sg);
      const __m256i n110 = _mm256_add_epi32(n100, sg), n001 = _mm256_add_epi32(origin, sb);
      const __m256i n101 = _mm256_add_epi32(n100, sb), n011 = _mm256_add_epi32(n010, sb), n111 = _mm256_add_epi32(n110, sb);
      const auto lerp = [](__m256 a, __m256 b, __m256 t) { return _mm256_fmadd_ps(t, _mm256_sub_ps(b, a), a); };
      for (int c = 0; c < 3; ++c) {
        const __m256 a = lerp(gather(data, origin, c), gather(data, n100, c), fx);
        const __m256 b = lerp(gather(data, n010, c), gather(data, n110, c), fx);
        const __m256 d = lerp(gather(data, n001, c), gather(data, n101, c), fx);
        const __m256 e = lerp(gather(data, n011, c), gather(data, n111, c), fx);
        out[c] = lerp(lerp(a, b, fy), lerp(d, e, fy), fz);
      }
    }
    for (int c = 0; c < 3; ++c) _mm256_storeu_ps(planes[c] + i, out[c]);
  }
  if (i < n) scalar_pixel_kernels().lut3d(data, size, tetrahedral, Tail(planes, i).planes, n - i);
}

void matrix(const float m[3][3], const float offset[3], float* const planes[3], std::size_t n) {
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    const __m256 r = _mm256_loadu_ps(planes[0] + i), g = _mm256_loadu_ps(planes[1] + i), b = _mm256_loadu_ps(planes[2] + i);
    for (int c = 0; c < 3; ++c) {
      __m256 v = _mm256_fmadd_ps(_mm256_set1_ps(m[c][0]), r, _mm256_set1_ps(offset[c]));
      v = _mm256_fmadd_ps(_mm256_set1_ps(m[c][1]), g, v);
      _mm256_storeu_ps(planes[c] + i, _mm256_fmadd_ps(_mm256_set1_ps(m[c][2]), b, v));
    }
  }
  if (i < n) scalar_pixel_kernels().matrix(m, offset, Tail(planes, i).planes, n - i);
}

__m256i channel_byte(const float* plane) {  // round half up, clamp, NaN -> 0 (max's second operand)
  const __m256 t = _mm256_fmadd_ps(_mm256_loadu_ps(plane), _mm256_set1_ps(255.0f), _mm256_set1_ps(0.5f));
  return _mm256_cvttps_epi32(_mm256_min_ps(_mm256_max_ps(t, _mm256_setzero_ps()), _mm256_set1_ps(255.0f)));
}

void to_bytes(const float* const planes[3], std::size_t n, std::uint8_t* rgba) {
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    __m256i pixel = _mm256_set1_epi32(static_cast<int>(0xff000000u));
    pixel = _mm256_or_si256(pixel, channel_byte(planes[0] + i));
    pixel = _mm256_or_si256(pixel, _mm256_slli_epi32(channel_byte(planes[1] + i), 8));
    pixel = _mm256_or_si256(pixel, _mm256_slli_epi32(channel_byte(planes[2] + i), 16));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(rgba + 4 * i), pixel);  // little-endian: R first
  }
  if (i < n) {
    const float* rest[3] = {planes[0] + i, planes[1] + i, planes[2] + i};
    scalar_pixel_kernels().to_bytes(rest, n - i, rgba + 4 * i);
  }
}

}  // namespace

const PixelKernels* avx2_pixel_kernels() {
  static const PixelKernels kernels{flatten, separable, lut3d, matrix, to_bytes};
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? &kernels : nullptr;
}

}  // namespace phongcl
