#include "phong_pipeline.h"

#include <stdexcept>

#include "peers/float_math.h"

namespace phongcl::halide_peer {

using namespace Halide;
using peer_math::kLn2High;
using peer_math::kLn2Low;
using peer_math::kLnSmallestNormal;
using peer_math::kSmallestNormal;

namespace {

// The peers' math (host/peers/phong_pixel.h, float_math.h), expression for expression: the same
// bit tricks, polynomials, selects and flush of specular factors below 2^-126.
struct Vec3 {
  Expr x, y, z;
};
Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Expr dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vec3 unit_or_zero(const Vec3& v) {
  const Expr largest = max(abs(v.x), max(abs(v.y), abs(v.z)));
  const Expr e = min(reinterpret<int32_t>(largest) >> 23, 253);
  const Expr scale = reinterpret<float>((254 - e) << 23);
  const Vec3 scaled{v.x * scale, v.y * scale, v.z * scale};
  const Expr length_sq = dot(scaled, scaled);
  const Expr to_unit = select(length_sq > 0.0f, 1.0f / sqrt(length_sq), 0.0f);
  return {scaled.x * to_unit, scaled.y * to_unit, scaled.z * to_unit};
}

Expr log_positive(const Expr& x, const Expr& one_minus_x) {
  const Expr subnormal = x < kSmallestNormal;
  const Expr bits = reinterpret<int32_t>(select(subnormal, x * 8388608.0f, x));
  Expr e = (bits >> 23) - select(subnormal, 127 + 23, 127);
  Expr f = reinterpret<float>((bits & 0x007fffff) | 0x3f800000);
  const Expr high = f > 1.41421356f;
  f = select(high, f * 0.5f, f);
  e = select(high, e + 1, e);
  const Expr near_one = abs(one_minus_x) < 0.29f;
  const Expr numerator = select(near_one, -one_minus_x, f - 1.0f);
  const Expr denominator = select(near_one, 2.0f - one_minus_x, f + 1.0f);
  const Expr exponent = select(near_one, 0.0f, cast<float>(e));
  const Expr s = numerator / denominator;
  const Expr s2 = s * s;
  const Expr series = s * (2.0f + s2 * (2.0f / 3 + s2 * (2.0f / 5 + s2 * (2.0f / 7 + s2 * (2.0f / 9)))));
  return exponent * kLn2High + (exponent * kLn2Low + series);
}

Expr exp_float(const Expr& y) {
  const Expr below = y < kLnSmallestNormal;
  const Expr clamped = select(below, kLnSmallestNormal, y);
  const Expr k = floor(clamped * 1.44269504f + 0.5f);
  const Expr r = (clamped - k * kLn2High) - k * kLn2Low;
  const Expr p = 1.0f + r * (1.0f + r * (1.0f / 2 + r * (1.0f / 6 + r * (1.0f / 24 + r * (1.0f / 120 + r * (1.0f / 720 + r * (1.0f / 5040)))))));
  const Expr scaled = p * reinterpret<float>((cast<int32_t>(k) + 127) << 23);
  return select(below, 0.0f, scaled);
}

Expr specular_power(const Expr& cos_vr, const Expr& one_minus_cos, const Expr& q) {
  const Expr positive = cos_vr > 0.0f;
  const Expr power = exp_float(q * log_positive(select(positive, cos_vr, 1.0f), one_minus_cos));
  return select(q == 0.0f, 1.0f, select(positive, power, 0.0f));
}

// Light k's contribution added to the six sums (diffuse rgb, specular rgb) of pixel i.
Tuple add_light(const FuncRef& sums, const Vec3& n, const Vec3& v, const Vec3& l, const Expr& q, const ImageParam& lights,
                const Expr& k) {
  const Expr ndl = dot(n, l);
  const Expr lit = ndl > 0.0f;
  const Expr two_ndl = 2.0f * ndl;
  const Vec3 r{two_ndl * n.x - l.x, two_ndl * n.y - l.y, two_ndl * n.z - l.z};
  const Vec3 v_minus_r = v - r;
  const Expr specular = select(lit, specular_power(dot(v, r), 0.5f * dot(v_minus_r, v_minus_r), q), 0.0f);
  const Expr diffuse = select(lit, ndl, 0.0f);
  const Tuple old(sums);
  return Tuple(old[0] + lights(k, kLightR) * diffuse, old[1] + lights(k, kLightG) * diffuse, old[2] + lights(k, kLightB) * diffuse,
               old[3] + lights(k, kLightR) * specular, old[4] + lights(k, kLightG) * specular, old[5] + lights(k, kLightB) * specular);
}

}  // namespace

const std::vector<Schedule>& schedules() {
  static const std::vector<Schedule> all = {
      {"vector64", "parallel chunks; per 64 pixels (four independent AVX-512 chains), the lights loop with the sums in registers"},
      {"vector32", "as vector64 with 32 pixels (two chains)"},
      {"vector16", "as vector64 with 16 pixels (one register per value)"},
      {"tile256-lights-outer", "parallel chunks; per 256-pixel tile, each light a loop over 16 vectors of 16 (state in L1)"},
      {"tile1024-lights-outer", "as tile256-lights-outer with 1024-pixel tiles"},
  };
  return all;
}

Func phong_pipeline(const PipelineInputs& in, const std::string& schedule) {
  Var i("i"), c("c");
  const Expr m = unsafe_promise_clamped(in.material(i) + 1, 0, in.materials.dim(0).extent() - 1);

  // Per pixel: unit normal, unit vector to the eye (the origin), shininess.
  Func pixel("pixel");
  {
    const Vec3 n = unit_or_zero({in.nx(i), in.ny(i), in.nz(i)});
    const Vec3 v = unit_or_zero({-in.px(i), -in.py(i), -in.pz(i)});
    pixel(i) = Tuple(n.x, n.y, n.z, v.x, v.y, v.z, in.materials(m, kShininess));
  }
  const Vec3 n{pixel(i)[0], pixel(i)[1], pixel(i)[2]};
  const Vec3 v{pixel(i)[3], pixel(i)[4], pixel(i)[5]};
  const Expr q = pixel(i)[6];

  Func sums("sums");
  sums(i) = Tuple(0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
  RDom point(0, in.point_count, "point");
  {
    const Vec3 to_light = Vec3{in.point_lights(point, kLightX), in.point_lights(point, kLightY), in.point_lights(point, kLightZ)} -
                          Vec3{in.px(i), in.py(i), in.pz(i)};
    sums(i) = add_light(sums(i), n, v, unit_or_zero(to_light), q, in.point_lights, point);
  }
  RDom directional(0, in.directional_count, "directional");
  {
    const ImageParam& d = in.directional_lights;
    sums(i) = add_light(sums(i), n, v, {d(directional, kLightX), d(directional, kLightY), d(directional, kLightZ)}, q, d, directional);
  }

  // ka La + kd sum_d + ks sum_s, alpha; the background's table entry has kd = ks = 0.
  Func rgba("rgba");
  const Tuple s(sums(i));
  const ImageParam& t = in.materials;
  rgba(c, i) = mux(c, {t(m, kAmbientR) + t(m, kKdR) * s[0] + t(m, kKsR) * s[3], t(m, kAmbientG) + t(m, kKdG) * s[1] + t(m, kKsG) * s[4],
                       t(m, kAmbientB) + t(m, kKdB) * s[2] + t(m, kKsB) * s[5], t(m, kAlpha)});

  // Every schedule: parallel chunks of `chunk` pixels, RGBA interleaved on store (c unrolled).
  Var chunk("chunk"), inner("inner"), tile("tile");
  rgba.bound(c, 0, 4).reorder(c, i).unroll(c).split(i, chunk, inner, in.chunk).parallel(chunk);
  auto per_vector = [&](int lanes) {
    rgba.split(inner, tile, i, lanes).vectorize(i);
    for (Func f : {pixel, sums}) f.compute_at(rgba, tile).vectorize(i);
    sums.update(0).vectorize(i);
    sums.update(1).vectorize(i);
  };
  auto per_tile = [&](int pixels) {
    rgba.split(inner, tile, i, pixels).vectorize(i, 16);
    pixel.compute_at(rgba, tile).vectorize(i, 16);
    sums.compute_at(rgba, tile).vectorize(i, 16);
    for (int u = 0; u < 2; ++u) sums.update(u).reorder(i, u == 0 ? point.x : directional.x).vectorize(i, 16);
  };
  if (schedule == "vector16") per_vector(16);
  else if (schedule == "vector32") per_vector(32);
  else if (schedule == "vector64") per_vector(64);
  else if (schedule == "tile256-lights-outer") per_tile(256);
  else if (schedule == "tile1024-lights-outer") per_tile(1024);
  else throw std::invalid_argument("unknown Halide schedule '" + schedule + "'");
  return rgba;
}

}  // namespace phongcl::halide_peer
