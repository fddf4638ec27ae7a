#include "gbuffer/edge_policy.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace phongcl {

namespace {

// Shorter filtered normals average directions more than 16 degrees apart: two surfaces.
constexpr double kMixedLength = 0.98;

// A unit normal stored as half comes back up to about 2^-10 short: lengths this close to 1 are 1.
constexpr double kUnitLength = 1.0 - 1.0 / 256.0;

bool is_background(const GBuffer& g, std::size_t i) { return g.material[i] < 0.0f; }

bool next_to_background(const GBuffer& g, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= g.width || ny >= g.height) continue;
      if (is_background(g, static_cast<std::size_t>(ny) * g.width + nx)) return true;
    }
  return false;
}

double normal_length(const GBuffer& g, std::size_t i) {
  return std::sqrt(double(g.normal[0][i]) * g.normal[0][i] + double(g.normal[1][i]) * g.normal[1][i] +
                   double(g.normal[2][i]) * g.normal[2][i]);
}

void divide_by_coverage(Planes3& colour, const Plane& coverage) {
  if (colour[0].empty()) return;
  for (std::size_t i = 0; i < coverage.size(); ++i)
    if (coverage[i] > 0.0f && coverage[i] < 1.0f)
      for (auto& plane : colour) plane[i] /= coverage[i];
}

std::array<double, 3> position_of(const GBuffer& g, std::size_t i) { return {g.position[0][i], g.position[1][i], g.position[2][i]}; }

// |dot(unit normal of j, P_i - P_j)| / |P_i - P_j|: 0 when pixel i lies on j's tangent plane.
double off_plane(const GBuffer& g, std::size_t i, std::size_t j) {
  const std::array<double, 3> pi = position_of(g, i), pj = position_of(g, j);
  double dot = 0.0, distance2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    dot += g.normal[c][j] * (pi[c] - pj[c]);
    distance2 += (pi[c] - pj[c]) * (pi[c] - pj[c]);
  }
  const double scale = normal_length(g, j) * std::sqrt(distance2);
  return scale > 0.0 ? std::abs(dot) / scale : 1.0;
}

void copy_pixel(Planes3& planes, std::size_t from, std::size_t to) {
  if (planes[0].empty()) return;
  for (auto& plane : planes) plane[to] = plane[from];
}

}  // namespace

std::size_t repair_surface_edges(GBuffer& g) {
  // Decide from the file's normals, then write: a repair must not feed the next pixel's choice.
  std::vector<std::pair<std::size_t, std::size_t>> repairs;  // pixel, neighbour
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * g.width + x;
      if (is_background(g, i) || next_to_background(g, x, y) || !(normal_length(g, i) < kMixedLength)) continue;
      std::size_t best = i;
      double best_off = 1.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= g.width || ny >= g.height) continue;
          const std::size_t j = static_cast<std::size_t>(ny) * g.width + nx;
          if (g.material[j] != g.material[i] || !(normal_length(g, j) >= kMixedLength)) continue;
          const double off = off_plane(g, i, j);
          if (off < best_off) best = j, best_off = off;
        }
      if (best != i) repairs.emplace_back(i, best);
    }
  for (const auto& [pixel, neighbour] : repairs) {
    copy_pixel(g.normal, neighbour, pixel);
    copy_pixel(g.kd, neighbour, pixel);
    copy_pixel(g.ks, neighbour, pixel);
  }
  return repairs.size();
}

std::size_t mark_sky_samples(GBuffer& g, const Plane& depth, float no_hit_depth) {
  std::size_t marked = 0;
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    const bool missed = depth.empty()
                            ? g.position[0][i] == 0.0f && g.position[1][i] == 0.0f && g.position[2][i] == 0.0f
                            : !std::isfinite(depth[i]) || depth[i] >= no_hit_depth;
    if (missed && !is_background(g, i)) {
      g.material[i] = -1.0f;
      ++marked;
    }
  }
  return marked;
}

const char* coverage_source_name(CoverageSource source) {
  switch (source) {
    case CoverageSource::none: return "none";
    case CoverageSource::alpha: return "alpha";
    case CoverageSource::normal_length: return "the normal's length next to background";
  }
  return "?";
}

CoverageSource estimate_coverage(GBuffer& g, const Plane& alpha) {
  const std::size_t pixels = g.pixel_count();
  bool partial_alpha = false;
  for (std::size_t i = 0; i < alpha.size() && !partial_alpha; ++i)
    partial_alpha = !is_background(g, i) && alpha[i] > 0.0f && alpha[i] < 1.0f;

  Plane coverage(pixels, 1.0f);
  bool any_partial = false;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * g.width + x;
      if (is_background(g, i)) continue;
      double c = 1.0;
      if (partial_alpha) c = alpha[i];
      else if (next_to_background(g, x, y)) c = normal_length(g, i);
      if (!partial_alpha && c > kUnitLength) c = 1.0;
      // NaN (a non-finite normal) stays 1: the pixel is counted as non-finite, not shaded.
      coverage[i] = static_cast<float>(std::clamp(std::isnan(c) ? 1.0 : c, 0.0, 1.0));
      any_partial |= coverage[i] < 1.0f;
    }
  if (!any_partial) return CoverageSource::none;
  divide_by_coverage(g.kd, coverage);
  divide_by_coverage(g.ks, coverage);
  g.coverage = std::move(coverage);
  return partial_alpha ? CoverageSource::alpha : CoverageSource::normal_length;
}

}  // namespace phongcl
