// The per-pixel loops with AVX2 and FMA, eight pixels a step (color/pixel_kernels.h); the last
// n % 8 pixels go through the scalar loops. This file alone is compiled with -mavx2 -mfma and runs
// only where the CPU has both; it uses intrinsics and no inline library templates, so none of its
// AVX2 code can stand in for the rest of the program's.
#include <immintrin.h>

#include "color/pixel_kernels.h"

namespace phongcl {

// Named so the install check can tell these runtime-dispatched functions from the baseline code.
namespace avx2 {
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

// color/display_math.h's table_lookup: bucket bits >> 16, linear in the low 16 bits. A cell's two
// ends are adjacent floats, gathered as one 64-bit element (two gathers of four, 10-15% faster than
// two of eight floats).
__m256 lookup(const float* table, __m256 value) {
  const __m256i bits = _mm256_castps_si256(value);
  const __m256i index = _mm256_srli_epi32(bits, 16);
  const __m256 fraction = _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_and_si256(bits, _mm256_set1_epi32(0xffff))),
                                        _mm256_set1_ps(1.0f / 65536.0f));
  const auto* base = reinterpret_cast<const long long*>(table);
  const __m256 low = _mm256_castsi256_ps(_mm256_i32gather_epi64(base, _mm256_castsi256_si128(index), 4));
  const __m256 high = _mm256_castsi256_ps(_mm256_i32gather_epi64(base, _mm256_extracti128_si256(index, 1), 4));
  // low = s0 e0 s1 e1 | s2 e2 s3 e3, high = s4 e4 s5 e5 | s6 e6 s7 e7
  const __m256 starts = _mm256_shuffle_ps(low, high, 0x88);  // s0 s1 s4 s5 | s2 s3 s6 s7
  const __m256 ends = _mm256_shuffle_ps(low, high, 0xdd);
  const __m256i order = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
  const __m256 start = _mm256_permutevar8x32_ps(starts, order), end = _mm256_permutevar8x32_ps(ends, order);
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

// Eight pixels' cells of a 3D LUT: the offset (in floats) of each cell's origin node, the steps
// (in floats) along r, g and b, and the fractions within the cell.
struct Cells {
  __m256i origin, step_r, step_g, step_b;
  __m256 fx, fy, fz;
  Cells(const float* const planes[3], std::size_t i, int size)
      : step_r(_mm256_set1_epi32(3)), step_g(_mm256_set1_epi32(3 * size)), step_b(_mm256_set1_epi32(3 * size * size)) {
    const __m256 last = _mm256_set1_ps(static_cast<float>(size - 1));
    const __m256i highest_cell = _mm256_set1_epi32(size - 2);
    __m256 f[3];
    __m256i cell[3];
    for (int c = 0; c < 3; ++c) {
      const __m256 at = grid_coordinate(_mm256_loadu_ps(planes[c] + i), last);
      cell[c] = _mm256_min_epi32(_mm256_cvttps_epi32(at), highest_cell);
      f[c] = _mm256_sub_ps(at, _mm256_cvtepi32_ps(cell[c]));
    }
    fx = f[0], fy = f[1], fz = f[2];
    origin = _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(cell[0], step_r), _mm256_mullo_epi32(cell[1], step_g)),
                              _mm256_mullo_epi32(cell[2], step_b));
  }
};

// Eight nodes' R, G, B (at float offsets `index`) as three planes: a 16-byte load per node (its RGB
// and one float beyond, inside the table's padding), then a 4x4 transpose of each 128-bit half.
// Faster than gathering each channel (12 gathers of eight for a tetrahedron's 4 corners).
void load_nodes(const float* data, __m256i index, __m256 rgb[3]) {
  alignas(32) int at[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(at), index);
  const auto pair = [&](int low, int high) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(data + at[low])), _mm_loadu_ps(data + at[high]), 1);
  };
  const __m256 p04 = pair(0, 4), p15 = pair(1, 5), p26 = pair(2, 6), p37 = pair(3, 7);
  const __m256 u0 = _mm256_unpacklo_ps(p04, p15), u1 = _mm256_unpackhi_ps(p04, p15);
  const __m256 u2 = _mm256_unpacklo_ps(p26, p37), u3 = _mm256_unpackhi_ps(p26, p37);
  rgb[0] = _mm256_shuffle_ps(u0, u2, 0x44);
  rgb[1] = _mm256_shuffle_ps(u0, u2, 0xee);
  rgb[2] = _mm256_shuffle_ps(u1, u3, 0x44);
}

// The scalar loop's tetrahedral interpolation without its branches: the tetrahedron's second
// corner is the cube's origin stepped along the axis of the largest fraction, its third the far
// corner stepped back along the axis of the smallest; the weights are the sorted fractions'
// differences.
void tetrahedral(const Cells& cell, const float* data, __m256 out[3]) {
  const __m256 xy = _mm256_cmp_ps(cell.fx, cell.fy, _CMP_GT_OQ), yz = _mm256_cmp_ps(cell.fy, cell.fz, _CMP_GT_OQ),
               xz = _mm256_cmp_ps(cell.fx, cell.fz, _CMP_GT_OQ);
  // largest: x if x > y and x > z, y if y >= x and y > z, else z; smallest: x if y >= x and z >= x,
  // y if x > y and z >= y, else z (never the largest's axis unless all are equal, where the
  // weights of both corners are 0)
  const __m256i largest = select(_mm256_and_ps(xy, xz), cell.step_r, select(_mm256_andnot_ps(xy, yz), cell.step_g, cell.step_b));
  const __m256 neither = _mm256_andnot_ps(_mm256_or_ps(xy, xz), _mm256_castsi256_ps(_mm256_set1_epi32(-1)));
  const __m256i smallest = select(neither, cell.step_r, select(_mm256_andnot_ps(yz, xy), cell.step_g, cell.step_b));
  const __m256i far = _mm256_add_epi32(cell.origin, _mm256_add_epi32(cell.step_r, _mm256_add_epi32(cell.step_g, cell.step_b)));
  const __m256 f_max = _mm256_max_ps(cell.fx, _mm256_max_ps(cell.fy, cell.fz));
  const __m256 f_min = _mm256_min_ps(cell.fx, _mm256_min_ps(cell.fy, cell.fz));
  const __m256 f_mid = _mm256_max_ps(_mm256_min_ps(cell.fx, cell.fy), _mm256_min_ps(_mm256_max_ps(cell.fx, cell.fy), cell.fz));
  const __m256 weight[4] = {_mm256_sub_ps(_mm256_set1_ps(1.0f), f_max), _mm256_sub_ps(f_max, f_mid),
                            _mm256_sub_ps(f_mid, f_min), f_min};
  const __m256i corner[4] = {cell.origin, _mm256_add_epi32(cell.origin, largest), _mm256_sub_epi32(far, smallest), far};
  for (int c = 0; c < 3; ++c) out[c] = _mm256_setzero_ps();
  for (int k = 0; k < 4; ++k) {
    __m256 rgb[3];
    load_nodes(data, corner[k], rgb);
    for (int c = 0; c < 3; ++c) out[c] = _mm256_fmadd_ps(weight[k], rgb[c], out[c]);
  }
}

__m256 gather(const float* data, __m256i index, int channel) { return _mm256_i32gather_ps(data + channel, index, 4); }

void trilinear(const Cells& cell, const float* data, __m256 out[3]) {
  const __m256i n100 = _mm256_add_epi32(cell.origin, cell.step_r), n010 = _mm256_add_epi32(cell.origin, cell.step_g);
  const __m256i n110 = _mm256_add_epi32(n100, cell.step_g), n001 = _mm256_add_epi32(cell.origin, cell.step_b);
  const __m256i n101 = _mm256_add_epi32(n100, cell.step_b), n011 = _mm256_add_epi32(n010, cell.step_b);
  const __m256i n111 = _mm256_add_epi32(n110, cell.step_b);
  const auto lerp = [](__m256 a, __m256 b, __m256 t) { return _mm256_fmadd_ps(t, _mm256_sub_ps(b, a), a); };
  for (int c = 0; c < 3; ++c) {
    const __m256 a = lerp(gather(data, cell.origin, c), gather(data, n100, c), cell.fx);
    const __m256 b = lerp(gather(data, n010, c), gather(data, n110, c), cell.fx);
    const __m256 d = lerp(gather(data, n001, c), gather(data, n101, c), cell.fx);
    const __m256 e = lerp(gather(data, n011, c), gather(data, n111, c), cell.fx);
    out[c] = lerp(lerp(a, b, cell.fy), lerp(d, e, cell.fy), cell.fz);
  }
}

void lut3d(const float* data, int size, bool tetrahedral_interpolation, float* const planes[3], std::size_t n) {
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    const Cells cell(planes, i, size);
    __m256 out[3];
    (tetrahedral_interpolation ? tetrahedral : trilinear)(cell, data, out);
    for (int c = 0; c < 3; ++c) _mm256_storeu_ps(planes[c] + i, out[c]);
  }
  if (i < n) scalar_pixel_kernels().lut3d(data, size, tetrahedral_interpolation, Tail(planes, i).planes, n - i);
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
}  // namespace avx2

const PixelKernels* avx2_pixel_kernels() {
  using namespace avx2;
  static const PixelKernels kernels{flatten, separable, lut3d, matrix, to_bytes};
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? &kernels : nullptr;
}

}  // namespace phongcl
