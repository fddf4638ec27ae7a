#pragma once
// Two accuracy bars, (a) far from the origin and (b) at highlight peaks, as seeded random
// G-buffers of many pixels: the default precision must stay within kBarRelative (kBarAbsolute near
// zero) of the long double oracle on both.
#include <string>
#include <utility>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/phong_shader.h"

namespace phongcl {

inline constexpr double kBarRelative = 1e-3;
inline constexpr double kBarAbsolute = 1e-6;

// (a) Surfaces, eye and lights all about `distance` from the origin, the eye and three point
// lights a few units from the surfaces, plus one directional light; random materials, q in
// [1, 1000]. Positions far from the origin are coarse floats (0.0625 apart at 1e6): the oracle uses
// those very floats, so what is measured is how the pipeline treats them.
std::pair<Scene, GBuffer> far_from_origin_scene(double distance, unsigned seed, int size = 64);

// (b) Every pixel near the peak of its highlight: the normal is the half vector of v and l turned
// by k / (2 sqrt(q)), so |v - r| is about k / sqrt(q) with k in [0, 4] (the highlight from 1 down to
// e^-8), q log-uniform in [1e2, 1e6] per pixel, specular only (ka = kd = 0) so that nothing hides
// its error. The eye is not at the origin, so rebasing on the host is part of what is measured.
std::pair<Scene, GBuffer> highlight_peak_scene(unsigned seed, int size = 64);

// One bar on one variant: the largest error over every shaded value of several seeded G-buffers.
struct BarFigure {
  std::string bar;      // "far from the origin (1e6)"
  Precision precision = Precision::precise;
  double max_rel = 0.0;
  std::size_t nan_values = 0;
  bool judged = false;  // the bar binds the default variant only; the others are reported
  bool passed() const { return !judged || (max_rel <= kBarRelative && nan_values == 0); }
};

// Both bars (far at 1e6 and 1e7, highlight peak) on every variant the device runs, `seeds`
// G-buffers of size x size pixels each. Throws what shade() throws, except half-storage's refusal
// of out-of-range values, which is recorded as an infinite error.
std::vector<BarFigure> measure_accuracy_bars(PhongShader& shader, int seeds = 3, int size = 64);

}  // namespace phongcl
