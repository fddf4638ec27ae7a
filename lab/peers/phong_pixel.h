#pragma once
// The Phong formula (docs/shading.md "The formula") for one pixel, in float, shared by both C++
// peers. Written for `omp simd` across pixels: no calls, no early returns, selects instead of
// branches, every lane reads the same light. Same degenerate policy as the kernel and the
// reference: a zero vector stays zero, pow(0, 0) = 1.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "peers/float_math.h"
#include "peers/packed_frame.h"

namespace phongcl::peer_math {

struct Vec3 {
  float x, y, z;
};
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Scales by a power of two near 1 / largest |component| first, so the squares neither overflow
// nor vanish in float; the scale comes from the exponent bits (exact, and no division).
inline Vec3 unit_or_zero(Vec3 v) {
  const float largest = std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z)));
  // 2^(127 - e) for largest in [2^(e-127), 2^(e-126)); e <= 253 keeps the scale a normal float.
  const std::int32_t e = std::min(std::bit_cast<std::int32_t>(largest) >> 23, 253);
  const float scale = std::bit_cast<float>((254 - e) << 23);
  const Vec3 scaled{v.x * scale, v.y * scale, v.z * scale};
  const float length_sq = dot(scaled, scaled);
  const float to_unit = length_sq > 0.0f ? 1.0f / std::sqrt(length_sq) : 0.0f;  // zero stays zero
  return {scaled.x * to_unit, scaled.y * to_unit, scaled.z * to_unit};
}

// max(0, cos_vr)^q with pow(0, 0) = 1. one_minus_cos = |v - r|^2 / 2 has no cancellation near the peak.
inline float specular_power(float cos_vr, float one_minus_cos, float q) {
  const bool positive = cos_vr > 0.0f;
  const float power = exp_float(q * log_positive(positive ? cos_vr : 1.0f, one_minus_cos));
  return q == 0.0f ? 1.0f : (positive ? power : 0.0f);
}

// Raw pointers into PackedFrame / PackedScene, taken once outside the pixel loop. The material
// tables point one past the background entry, so index -1 (background) is valid.
struct SceneView {
  const float *ambient_r, *ambient_g, *ambient_b, *kd_r, *kd_g, *kd_b, *ks_r, *ks_g, *ks_b, *shininess, *alpha;
  const float *point_x, *point_y, *point_z, *point_r, *point_g, *point_b;
  const float *dir_x, *dir_y, *dir_z, *dir_r, *dir_g, *dir_b;
  int point_count, directional_count;
};
struct FrameView {
  const float *px, *py, *pz, *nx, *ny, *nz;
  const std::int32_t* material;
};

inline SceneView view_of(const PackedScene& s) {
  return {s.ambient_r.data() + 1, s.ambient_g.data() + 1, s.ambient_b.data() + 1, s.kd_r.data() + 1,
          s.kd_g.data() + 1,      s.kd_b.data() + 1,      s.ks_r.data() + 1,      s.ks_g.data() + 1,
          s.ks_b.data() + 1,      s.shininess.data() + 1, s.alpha.data() + 1,     s.point_x.data(),
          s.point_y.data(),       s.point_z.data(),       s.point_r.data(),       s.point_g.data(),
          s.point_b.data(),       s.dir_x.data(),         s.dir_y.data(),         s.dir_z.data(),
          s.dir_r.data(),         s.dir_g.data(),         s.dir_b.data(),         s.point_count(),
          s.directional_count()};
}
inline FrameView view_of(const PackedFrame& f) {
  return {f.px.data(), f.py.data(), f.pz.data(), f.nx.data(), f.ny.data(), f.nz.data(), f.material.data()};
}

// What one light adds, per unit of its colour: max(0, n.l) and the specular factor (both 0 when
// n.l <= 0: back-facing, grazing, or a zero vector). l is the unit vector towards the light.
struct LightTerm {
  float diffuse, specular;
};
inline LightTerm light_term(Vec3 n, Vec3 v, Vec3 l, float q) {
  const float ndl = dot(n, l);
  const bool lit = ndl > 0.0f;
  const float two_ndl = 2.0f * ndl;
  const Vec3 r{two_ndl * n.x - l.x, two_ndl * n.y - l.y, two_ndl * n.z - l.z};
  const Vec3 v_minus_r = v - r;
  const float specular = specular_power(dot(v, r), 0.5f * dot(v_minus_r, v_minus_r), q);
  return {lit ? ndl : 0.0f, lit ? specular : 0.0f};
}

// Sums over lights of Li * max(0, n.l) and Li * spec; the material multiplies once at the end.
struct LightSums {
  float diffuse_r = 0, diffuse_g = 0, diffuse_b = 0, specular_r = 0, specular_g = 0, specular_b = 0;

  void add(float r, float g, float b, LightTerm term) {
    diffuse_r += r * term.diffuse;
    diffuse_g += g * term.diffuse;
    diffuse_b += b * term.diffuse;
    specular_r += r * term.specular;
    specular_g += g * term.specular;
    specular_b += b * term.specular;
  }
};

// The pixel's RGBA into out[0..3]: ka La + kd sum_d + ks sum_s and alpha 1; a background pixel
// (material -1, zero sums) gets its table entry: the background colour and alpha 0.
inline void write_pixel(const SceneView& scene, std::int32_t m, const LightSums& sums, float* out) {
  out[0] = scene.ambient_r[m] + scene.kd_r[m] * sums.diffuse_r + scene.ks_r[m] * sums.specular_r;
  out[1] = scene.ambient_g[m] + scene.kd_g[m] * sums.diffuse_g + scene.ks_g[m] * sums.specular_g;
  out[2] = scene.ambient_b[m] + scene.kd_b[m] * sums.diffuse_b + scene.ks_b[m] * sums.specular_b;
  out[3] = scene.alpha[m];
}

}  // namespace phongcl::peer_math
