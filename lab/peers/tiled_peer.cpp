// cpp-tiled: the tiled light culling of ISPC's examples/cpu/deferred in C++, on every core (OpenMP)
// with each tile row's pixels vectorised (`omp simd`): per tile, the box of its shaded positions and
// the list of lights whose bounding sphere meets it (through boxes of coarse_tiles x coarse_tiles
// tiles first), then the tile's pixels shaded from that list, each row skipping the listed lights
// whose range misses all of its pixels, as the kernel's work-items do.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "peers/peers.h"
#include "peers/phong_pixel.h"
#include "peers/simd_request.h"

namespace phongcl {

namespace {

using namespace peer_math;

constexpr std::size_t kRow = 16;  // pixels per simd loop: one AVX-512 register of floats

struct Box {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  bool empty = true;
};

struct TileRect {
  int x0, y0, x1, y1;
};

TileRect tile_rect(std::size_t tile, int tiles_x, int tile_size, int width, int height) {
  const int tx = static_cast<int>(tile % static_cast<std::size_t>(tiles_x));
  const int ty = static_cast<int>(tile / static_cast<std::size_t>(tiles_x));
  return {tx * tile_size, ty * tile_size, std::min((tx + 1) * tile_size, width), std::min((ty + 1) * tile_size, height)};
}

Box tile_box(const PackedFrame& f, const TileRect& r, int width, std::size_t& shaded) {
  Box box;
  shaded = 0;
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      if (f.material[i] == kPeerBackground) continue;
      box.empty = false;
      ++shaded;
      const float p[3] = {f.px[i], f.py[i], f.pz[i]};
      for (int a = 0; a < 3; ++a) box.lo[a] = std::min(box.lo[a], p[a]), box.hi[a] = std::max(box.hi[a], p[a]);
    }
  }
  return box;
}

// The lights of `candidates` whose bounding sphere meets the box (every one without a range).
void cull(const PackedScene& s, const Box& box, const std::vector<int>& candidates, std::vector<int>& list) {
  list.clear();
  if (box.empty) return;
  for (int k : candidates) {
    const float r = s.bound_radius[k];
    const float c[3] = {s.bound_x[k], s.bound_y[k], s.bound_z[k]};
    float d2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
      const float outside = std::max(std::max(box.lo[a] - c[a], c[a] - box.hi[a]), 0.0f);
      d2 += outside * outside;
    }
    if (r < 0.0f || d2 <= r * r) list.push_back(k);
  }
}

// One light's shape, loaded once before the simd loop over a row.
struct Shape {
  float inverse_range, axis_x, axis_y, axis_z, versine_inner, versine_outer, inverse_cone_width;
  float powers;  // of 1/d, 0 to 3 (a float: an int compare in the loop stops GCC vectorising it)
};

Shape shape_of(const PackedScene& s, int k) {
  return {s.inverse_range[k], s.axis_x[k],    s.axis_y[k],           s.axis_z[k],
          s.versine_inner[k], s.versine_outer[k], s.inverse_cone_width[k], s.falloff_power[k]};
}

// Clamped to [0, 1], NaN to 0, with compares: std::fmin and std::fmax (their NaN rules) kept GCC 12
// from vectorising the point-light loop at all ("no vectype for stmt"), so it ran scalar.
inline float saturate(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }

// F = falloff(d) * window(d) * cone(l) for l = to_light / d, as the kernel's light_shape.h states
// it (l = (ux, uy, uz)); the powers of 1/d as uniform selects, so the simd loop has no inner loop
// or branch. (Floats, not a named Vec3: GCC would keep that in a per-lane array and gather.)
inline float light_weight(Shape shape, float d, float inverse_d, float ux, float uy, float uz) {
  const float x = d * shape.inverse_range, x2 = x * x;
  const float t = saturate(1.0f - x2 * x2);
  const float ox = -ux - shape.axis_x, oy = -uy - shape.axis_y, oz = -uz - shape.axis_z;  // -l - axis
  const float versine = 0.5f * (ox * ox + oy * oy + oz * oz);                               // 1 - c
  const float e = versine <= shape.versine_inner ? 1.0f : saturate((shape.versine_outer - versine) * shape.inverse_cone_width);
  const float bounded = t * t * (e * e * (3.0f - 2.0f * e));
  const float once = shape.powers >= 1.0f ? inverse_d : 1.0f, twice = shape.powers >= 2.0f ? inverse_d : 1.0f;
  const float thrice = shape.powers >= 3.0f ? inverse_d : 1.0f;
  const float weight = ((bounded * once) * twice) * thrice;
  return bounded > 0.0f ? weight : 0.0f;
}

// Whether light k's range (1.01 times it, as the kernel's skip) holds any of the row's first
// `count` positions; true for a light without a range.
bool row_in_range(const PackedScene& s, int k, const float* px, const float* py, const float* pz, std::size_t count) {
  const float inverse_range = s.inverse_range[k];
  if (inverse_range <= 0.0f) return true;
  const float lx = s.point_x[k], ly = s.point_y[k], lz = s.point_z[k];
  float nearest_sq = INFINITY;
PHONGCL_SIMD(reduction(min : nearest_sq))
  for (std::size_t j = 0; j < count; ++j) {
    const float tx = lx - px[j], ty = ly - py[j], tz = lz - pz[j];
    nearest_sq = std::min(nearest_sq, tx * tx + ty * ty + tz * tz);
  }
  return nearest_sq * (inverse_range * inverse_range) <= 1.01f;
}

// One row of up to kRow pixels of a tile, lit by the tile's list and every directional light. A
// listed light whose range misses every pixel of the row adds exactly 0 and is skipped.
void shade_row(const FrameView& f, const SceneView& view, const PackedScene& s, const std::vector<int>& list,
               std::size_t first, std::size_t count, float* rgba) {
  alignas(64) float px[kRow] = {}, py[kRow] = {}, pz[kRow] = {}, nx[kRow] = {}, ny[kRow] = {}, nz[kRow] = {};
  alignas(64) float vx[kRow] = {}, vy[kRow] = {}, vz[kRow] = {}, q[kRow] = {};
  alignas(64) float dr[kRow] = {}, dg[kRow] = {}, db[kRow] = {}, sr[kRow] = {}, sg[kRow] = {}, sb[kRow] = {};
  for (std::size_t j = 0; j < count; ++j) {
    const std::size_t i = first + j;
    px[j] = f.px[i], py[j] = f.py[i], pz[j] = f.pz[i];
    const Vec3 n = unit_or_zero({f.nx[i], f.ny[i], f.nz[i]}), v = unit_or_zero({-f.px[i], -f.py[i], -f.pz[i]});
    nx[j] = n.x, ny[j] = n.y, nz[j] = n.z, vx[j] = v.x, vy[j] = v.y, vz[j] = v.z;
    q[j] = view.shininess[f.material[i]];
  }
  for (int k : list) {
    if (!row_in_range(s, k, px, py, pz, count)) continue;
    const float lx = s.point_x[k], ly = s.point_y[k], lz = s.point_z[k];
    const float cr = s.point_r[k], cg = s.point_g[k], cb = s.point_b[k];
    const Shape shape = shape_of(s, k);
PHONGCL_SIMD()
    for (std::size_t j = 0; j < kRow; ++j) {
      const float tx = lx - px[j], ty = ly - py[j], tz = lz - pz[j];
      const float d2 = tx * tx + ty * ty + tz * tz;
      const float inverse_d = d2 > 0.0f ? 1.0f / std::sqrt(d2) : 0.0f;
      const float ux = tx * inverse_d, uy = ty * inverse_d, uz = tz * inverse_d;
      const float weight = light_weight(shape, d2 * inverse_d, inverse_d, ux, uy, uz);
      const LightTerm term = light_term({nx[j], ny[j], nz[j]}, {vx[j], vy[j], vz[j]}, {ux, uy, uz}, q[j]);
      const float diffuse = term.diffuse * weight, specular = term.specular * weight;
      dr[j] += cr * diffuse, dg[j] += cg * diffuse, db[j] += cb * diffuse;
      sr[j] += cr * specular, sg[j] += cg * specular, sb[j] += cb * specular;
    }
  }
  for (int k = 0; k < s.directional_count(); ++k) {
    const Vec3 l{s.dir_x[k], s.dir_y[k], s.dir_z[k]};
PHONGCL_SIMD()
    for (std::size_t j = 0; j < kRow; ++j) {
      const LightTerm term = light_term({nx[j], ny[j], nz[j]}, {vx[j], vy[j], vz[j]}, l, q[j]);
      dr[j] += s.dir_r[k] * term.diffuse, dg[j] += s.dir_g[k] * term.diffuse, db[j] += s.dir_b[k] * term.diffuse;
      sr[j] += s.dir_r[k] * term.specular, sg[j] += s.dir_g[k] * term.specular, sb[j] += s.dir_b[k] * term.specular;
    }
  }
  for (std::size_t j = 0; j < count; ++j)
    write_pixel(view, f.material[first + j], {dr[j], dg[j], db[j], sr[j], sg[j], sb[j]}, rgba + 4 * (first + j));
}

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::string describe(TiledPeerSchedule schedule) {
  return "tiles " + std::to_string(schedule.tile_size) + ", coarse " + std::to_string(schedule.coarse_tiles) + ", " +
         std::to_string(schedule.tiles_per_task) + " tiles/task";
}

TiledPeerStats shade_tiled(const PackedFrame& frame, const PackedScene& scene, int width, int height,
                           TiledPeerSchedule schedule, float* rgba) {
  const int tile_size = schedule.tile_size, coarse_tiles = schedule.coarse_tiles, tiles_per_task = schedule.tiles_per_task;
  const FrameView f = view_of(frame);
  const SceneView view = view_of(scene);
  const int tiles_x = (width + tile_size - 1) / tile_size, tiles_y = (height + tile_size - 1) / tile_size;
  const auto tiles = static_cast<std::int64_t>(tiles_x) * tiles_y;
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(tiles));
  TiledPeerStats stats;
  const auto start = std::chrono::steady_clock::now();
  // Culling and shading as separate passes, so the culling time can be reported apart; dynamic
  // schedules where tiles differ in how many lights they keep. Two levels: every light against
  // boxes of coarse_tiles x coarse_tiles tiles, then each tile against its coarse box's list.
  std::vector<Box> boxes(static_cast<std::size_t>(tiles));
  std::vector<std::size_t> shaded(static_cast<std::size_t>(tiles));
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < tiles; ++t)
    boxes[t] = tile_box(frame, tile_rect(static_cast<std::size_t>(t), tiles_x, tile_size, width, height), width, shaded[t]);
  const int coarse_x = (tiles_x + coarse_tiles - 1) / coarse_tiles, coarse_y = (tiles_y + coarse_tiles - 1) / coarse_tiles;
  const auto coarse_of = [&](std::int64_t t) {
    return t / tiles_x / coarse_tiles * coarse_x + t % tiles_x / coarse_tiles;
  };
  std::vector<Box> coarse_boxes(static_cast<std::size_t>(coarse_x) * coarse_y);
  for (std::int64_t t = 0; t < tiles; ++t) {
    if (boxes[t].empty) continue;
    Box& coarse = coarse_boxes[coarse_of(t)];
    coarse.empty = false;
    for (int a = 0; a < 3; ++a) coarse.lo[a] = std::min(coarse.lo[a], boxes[t].lo[a]), coarse.hi[a] = std::max(coarse.hi[a], boxes[t].hi[a]);
  }
  std::vector<int> every_light(static_cast<std::size_t>(scene.point_count()));
  for (int k = 0; k < scene.point_count(); ++k) every_light[k] = k;
  std::vector<std::vector<int>> coarse_lists(coarse_boxes.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(coarse_boxes.size()); ++c)
    cull(scene, coarse_boxes[c], every_light, coarse_lists[c]);
  double kept_pairs = 0.0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : kept_pairs)
  for (std::int64_t t = 0; t < tiles; ++t) {
    std::vector<int>& list = lists[static_cast<std::size_t>(t)];
    cull(scene, boxes[t], coarse_lists[coarse_of(t)], list);
    kept_pairs += static_cast<double>(shaded[t]) * static_cast<double>(list.size());
  }
  stats.kept_pairs = kept_pairs;
  stats.culling_ms = since(start);
  const auto shading = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(dynamic, tiles_per_task)
  for (std::int64_t t = 0; t < tiles; ++t) {
    const TileRect r = tile_rect(static_cast<std::size_t>(t), tiles_x, tile_size, width, height);
    for (int y = r.y0; y < r.y1; ++y) {
      for (int x = r.x0; x < r.x1; x += static_cast<int>(kRow)) {
        const std::size_t first = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        shade_row(f, view, scene, lists[static_cast<std::size_t>(t)], first,
                  std::min<std::size_t>(kRow, static_cast<std::size_t>(r.x1 - x)), rgba);
      }
    }
  }
  stats.shading_ms = since(shading);
  return stats;
}

}  // namespace phongcl
