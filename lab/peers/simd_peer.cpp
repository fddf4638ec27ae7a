#include <algorithm>
#include <cstdint>

#include "peers/peers.h"
#include "peers/phong_pixel.h"
#include "peers/simd_request.h"

namespace phongcl {

namespace {

using namespace peer_math;

// Pixels per block: one AVX-512 register of floats. GCC cannot vectorise a pixel loop around two
// light loops, so the loops are turned inside out: per block, each light is one `omp simd` loop
// over the block's pixels, with the per-pixel state in small arrays that stay in L1. (No named
// Vec3 inside the simd loops: GCC would keep it in a per-lane array and gather from it.)
constexpr std::size_t kBlock = kPeerPadding;

struct Block {
  alignas(64) float px[kBlock], py[kBlock], pz[kBlock], nx[kBlock], ny[kBlock], nz[kBlock];
  alignas(64) float vx[kBlock], vy[kBlock], vz[kBlock], q[kBlock];
  alignas(64) float dr[kBlock], dg[kBlock], db[kBlock], sr[kBlock], sg[kBlock], sb[kBlock];

  Vec3 p(std::size_t j) const { return {px[j], py[j], pz[j]}; }
  Vec3 n(std::size_t j) const { return {nx[j], ny[j], nz[j]}; }
  Vec3 v(std::size_t j) const { return {vx[j], vy[j], vz[j]}; }
  void add(std::size_t j, float r, float g, float b, LightTerm term) {
    dr[j] += r * term.diffuse, dg[j] += g * term.diffuse, db[j] += b * term.diffuse;
    sr[j] += r * term.specular, sg[j] += g * term.specular, sb[j] += b * term.specular;
  }
  void set_unit(std::size_t j, Vec3 normal, Vec3 to_eye) {
    const Vec3 n = unit_or_zero(normal), v = unit_or_zero(to_eye);
    nx[j] = n.x, ny[j] = n.y, nz[j] = n.z, vx[j] = v.x, vy[j] = v.y, vz[j] = v.z;
  }
};

void shade_block(const FrameView& f, const SceneView& s, std::size_t first, std::size_t count, float* rgba) {
  Block b;
PHONGCL_SIMD()
  for (std::size_t j = 0; j < kBlock; ++j) {  // whole blocks: the frame's planes are padded
    const std::size_t i = first + j;
    b.px[j] = f.px[i], b.py[j] = f.py[i], b.pz[j] = f.pz[i];
    b.set_unit(j, {f.nx[i], f.ny[i], f.nz[i]}, {-f.px[i], -f.py[i], -f.pz[i]});  // the eye is the origin
    b.q[j] = s.shininess[f.material[i]];
    b.dr[j] = b.dg[j] = b.db[j] = b.sr[j] = b.sg[j] = b.sb[j] = 0.0f;
  }
  for (int k = 0; k < s.point_count; ++k) {
    const Vec3 light{s.point_x[k], s.point_y[k], s.point_z[k]};
PHONGCL_SIMD()
    for (std::size_t j = 0; j < kBlock; ++j) {
      b.add(j, s.point_r[k], s.point_g[k], s.point_b[k], light_term(b.n(j), b.v(j), unit_or_zero(light - b.p(j)), b.q[j]));
    }
  }
  for (int k = 0; k < s.directional_count; ++k) {
    const Vec3 l{s.dir_x[k], s.dir_y[k], s.dir_z[k]};
PHONGCL_SIMD()
    for (std::size_t j = 0; j < kBlock; ++j) {
      b.add(j, s.dir_r[k], s.dir_g[k], s.dir_b[k], light_term(b.n(j), b.v(j), l, b.q[j]));
    }
  }
PHONGCL_SIMD()
  for (std::size_t j = 0; j < count; ++j) {
    write_pixel(s, f.material[first + j], {b.dr[j], b.dg[j], b.db[j], b.sr[j], b.sg[j], b.sb[j]}, rgba + 4 * (first + j));
  }
}

}  // namespace

// Static schedule: every block costs the same (no data-dependent exits), so equal contiguous
// chunks balance and each core streams its own part of every plane.
void shade_simd(const PackedFrame& frame, const PackedScene& scene, float* rgba) {
  const FrameView f = view_of(frame);
  const SceneView s = view_of(scene);
  const auto blocks = static_cast<std::int64_t>((frame.pixels + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::size_t first = static_cast<std::size_t>(b) * kBlock;
    shade_block(f, s, first, std::min(kBlock, frame.pixels - first), rgba);
  }
}

}  // namespace phongcl
