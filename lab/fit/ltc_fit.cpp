#include "fit/ltc_fit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "fit/ggx_lobe.h"
#include "fit/nelder_mead.h"

namespace phongcl {

using std::numbers::pi;

namespace {

// Stratified samples per axis: the objective's (from each of the two distributions), and the
// magnitude's and mean direction's (from the lobe alone, once per entry).
constexpr int error_strata = 32, moment_strata = 128;

// An LTC: M = [X Y Z] [[a, 0, b], [0, c, 0], [d, 0, 1]], Z the lobe's mean direction: every isotropic
// LTC up to scale (Heitz et al.'s fit leaves d at 0; with it the fit error at grazing views halves).
struct Ltc {
  glm::dmat3 m{1.0}, inverse{1.0};
  double inverse_det = 1.0;

  double density(const glm::dvec3& w) const {
    const glm::dvec3 original = inverse * w;
    const double length = glm::length(original);
    const double cosine = original.z / length;
    return cosine > 0.0 ? cosine / pi * inverse_det / (length * length * length) : 0.0;
  }
  glm::dvec3 sample(double xi1, double xi2) const {
    const double r = std::sqrt(xi1), phi = 2.0 * pi * xi2;
    return glm::normalize(m * glm::dvec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0 - xi1, 0.0))));
  }
};

Ltc make_ltc(const glm::dvec3& mean, const FitPoint& p) {
  const glm::dvec3 z = mean, x(z.z, 0.0, -z.x), y(0.0, 1.0, 0.0);
  const double a = std::max(std::abs(p[0]), 1e-7), c = std::max(std::abs(p[1]), 1e-7);
  const glm::dmat3 shape(glm::dvec3(a, 0.0, p[3]), glm::dvec3(0.0, c, 0.0), glm::dvec3(p[2], 0.0, 1.0));
  Ltc ltc;
  ltc.m = glm::dmat3(x, y, z) * shape;
  ltc.inverse = glm::inverse(ltc.m);
  ltc.inverse_det = std::abs(glm::determinant(ltc.inverse));
  return ltc;
}

struct Moments {
  double magnitude = 0.0;
  glm::dvec3 mean{0.0, 0.0, 1.0};
};

// The lobe's integral and mean direction by its own importance sampling.
Moments lobe_moments(const GgxLobe& lobe, const glm::dvec3& v) {
  double sum = 0.0;
  glm::dvec3 direction(0.0);
  for (int i = 0; i < moment_strata; ++i)
    for (int j = 0; j < moment_strata; ++j) {
      const glm::dvec3 l = lobe.sample(v, (i + 0.5) / moment_strata, (j + 0.5) / moment_strata);
      const double pdf = lobe.sample_density(v, l);
      if (!(pdf > 0.0)) continue;
      const double weight = lobe.value(v, l) / pdf;
      sum += weight;
      direction += weight * l;
    }
  Moments moments;
  moments.magnitude = sum / (moment_strata * moment_strata) / pi;
  direction.y = 0.0;  // the lobe is symmetric about the plane of n and v
  if (glm::length(direction) > 0.0) moments.mean = glm::normalize(direction);
  return moments;
}

// The integral of |lobe / (pi magnitude) - ltc|^power (power 1 or 3), by both distributions'
// samples with the balance heuristic.
double fit_error(const GgxLobe& lobe, const glm::dvec3& v, double magnitude, const Ltc& ltc, int power) {
  double sum = 0.0;
  auto add = [&](const glm::dvec3& w) {
    const double target = lobe.value(v, w) / (pi * magnitude), fitted = ltc.density(w);
    const double pdf = lobe.sample_density(v, w) + fitted;
    const double difference = std::abs(target - fitted);
    if (pdf > 0.0) sum += (power == 3 ? difference * difference * difference : difference) / pdf;
  };
  for (int i = 0; i < error_strata; ++i)
    for (int j = 0; j < error_strata; ++j) {
      const double xi1 = (i + 0.5) / error_strata, xi2 = (j + 0.5) / error_strata;
      add(ltc.sample(xi1, xi2));
      add(lobe.sample(v, xi1, xi2));
    }
  return sum / (error_strata * error_strata);
}

}  // namespace

double ltc_node_roughness(int i, int size) { return std::max(double(i) / (size - 1), ltc_roughness_min); }

double ltc_node_cos_view(int j, int size) {
  const double u = double(j) / (size - 1);
  return std::max(1.0 - u * u, ltc_cos_view_min);
}

std::vector<LtcEntry> fit_ltc_table(int size) {
  std::vector<LtcEntry> table(std::size_t(size) * size);
  FitPoint row_start{1.0, 1.0, 0.0, 0.0};  // roughness 1 at normal incidence is near a cosine
  for (int i = size - 1; i >= 0; --i) {
    const GgxLobe lobe(ltc_node_roughness(i, size));
    FitPoint start = row_start;
    for (int j = 0; j < size; ++j) {
      const double cos_view = ltc_node_cos_view(j, size);
      const glm::dvec3 v(std::sqrt(1.0 - cos_view * cos_view), 0.0, cos_view);
      const Moments moments = lobe_moments(lobe, v);
      auto objective = [&](const FitPoint& p) { return fit_error(lobe, v, moments.magnitude, make_ltc(moments.mean, p), 3); };
      const double step = 0.05 * std::max(std::abs(start[0]), 1e-3);
      const FitPoint fitted = nelder_mead(objective, start, step, 400, 1e-6);
      const Ltc ltc = make_ltc(moments.mean, fitted);
      LtcEntry& entry = table[std::size_t(i) * size + j];
      entry.roughness = lobe.roughness();
      entry.cos_view = cos_view;
      entry.inverse = ltc.inverse / ltc.inverse[1][1];
      entry.magnitude = moments.magnitude;
      entry.l3_error = objective(fitted);
      entry.l1_error = fit_error(lobe, v, moments.magnitude, ltc, 1);
      start = fitted;
      if (j == 0) row_start = fitted;
    }
  }
  return table;
}

}  // namespace phongcl
