#include "fit/ggx_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace phongcl {

namespace {

using std::numbers::pi;

// Smith's Lambda for GGX at cosine c (Heitz 2014, eq. 72).
double lambda(double alpha, double c) {
  return 0.5 * (std::sqrt(1.0 + alpha * alpha * std::max(1.0 / (c * c) - 1.0, 0.0)) - 1.0);
}

// The unpolarised reflectance of a dielectric of relative index eta >= 1 at incidence cosine c, from
// Snell's law and the amplitude coefficients.
double dielectric_reflectance(double c, double eta) {
  const double t = std::sqrt(std::max(1.0 - (1.0 - c * c) / (eta * eta), 0.0));
  const double rs = (c - eta * t) / (c + eta * t), rp = (eta * c - t) / (eta * c + t);
  return 0.5 * (rs * rs + rp * rp);
}

// The mean of value(h.v, l) over GGX's visible normals h for view cosine mu (the view in the xz plane),
// l the mirror of v about h; directions below the horizon count 0. Heitz 2018, "Sampling the GGX
// distribution of visible normals": the view stretched to alpha 1, a point of the unit disk squeezed
// into the projected half disk, lifted to the hemisphere, unstretched. The disk is taken as n x n
// equal-area cells (radius sqrt(u1), angle 2 pi u2) at their midpoints.
template <typename Value>
double visible_normal_mean(double alpha, double mu, int n, Value value) {
  const glm::dvec3 v(std::sqrt(std::max(1.0 - mu * mu, 0.0)), 0.0, mu);
  const glm::dvec3 stretched = glm::normalize(glm::dvec3(alpha * v.x, alpha * v.y, v.z));
  const bool upright = stretched.x * stretched.x <= 1e-7;
  const glm::dvec3 t1 = upright ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 t2 = upright ? glm::dvec3(0.0, 1.0, 0.0) : glm::cross(stretched, t1);
  const double squeeze = 0.5 * (1.0 + stretched.z);
  double sum = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const double r = std::sqrt((a + 0.5) / n), angle = 2.0 * pi * (b + 0.5) / n;
      const double x = r * std::cos(angle);
      const double y = (1.0 - squeeze) * std::sqrt(1.0 - x * x) + squeeze * r * std::sin(angle);
      const glm::dvec3 lifted = x * t1 + y * t2 + std::sqrt(std::max(1.0 - x * x - y * y, 0.0)) * stretched;
      const glm::dvec3 h = glm::normalize(glm::dvec3(alpha * lifted.x, alpha * lifted.y, std::max(lifted.z, 0.0)));
      const double h_dot_v = glm::dot(h, v);
      const glm::dvec3 l = 2.0 * h_dot_v * h - v;
      if (l.z > 0.0) sum += value(h_dot_v, l.z);
    }
  return sum / (static_cast<double>(n) * n);
}

double clamped_axis(int k, int size, double low, double high) {
  return std::clamp(static_cast<double>(k) / (size - 1), low, high);
}

void append_table(std::string& text, const char* name, const std::vector<float>& values, int row) {
  text += "PRINCIPLED_TABLE " + std::string(name) + "[" + std::to_string(values.size()) + "] = {\n";
  char number[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(number, sizeof number, "%.7ef", static_cast<double>(values[i]));
    text += (i % row == 0 ? "  " : " ") + std::string(number) + (i + 1 < values.size() ? "," : "");
    if ((i + 1) % row == 0 || i + 1 == values.size()) text += "\n";
  }
  text += "};\n";
}

}  // namespace

double index_of_axis(double z) {
  const double root = std::sqrt(std::min(z * z * z * z, 0.99));
  return (1.0 + root) / (1.0 - root);
}

// The light single-scattering GGX reflects, each direction weighted by weight(h.v): the estimator of
// single scattering over visible normals, G2 / G1(v), times the weight.
template <typename Weight>
double ggx_weighted_albedo(double roughness, double mu, int n, Weight weight) {
  const double alpha = roughness * roughness, lambda_v = lambda(alpha, mu);
  return visible_normal_mean(alpha, mu, n, [&](double h_dot_v, double l_z) {
    return weight(h_dot_v) * (1.0 + lambda_v) / (1.0 + lambda_v + lambda(alpha, l_z));
  });
}

double ggx_albedo(double roughness, double mu, int n) {
  return ggx_weighted_albedo(roughness, mu, n, [](double) { return 1.0; });
}

double ggx_schlick_factor(double roughness, double mu, int n) {
  return ggx_weighted_albedo(roughness, mu, n, [](double c) { return std::pow(1.0 - c, 5.0); }) / ggx_albedo(roughness, mu, n);
}

double ggx_f82_factor(double roughness, double mu, int n) {
  return ggx_weighted_albedo(roughness, mu, n, [](double c) { return c * std::pow(1.0 - c, 6.0); }) /
         ggx_albedo(roughness, mu, n);
}

double ggx_average_albedo(double roughness, int mu_points, int n) {
  double sum = 0.0;
  for (int k = 0; k < mu_points; ++k) {
    const double mu = (k + 0.5) / mu_points;
    sum += 2.0 * mu * ggx_albedo(roughness, mu, n);
  }
  return sum / mu_points;
}

double ggx_fresnel_interpolation(double roughness, double mu, double index, int n) {
  const double f0 = std::pow((index - 1.0) / (index + 1.0), 2.0);
  return visible_normal_mean(roughness * roughness, mu, n, [&](double h_dot_v, double) {
    return std::clamp((dielectric_reflectance(h_dot_v, index) - f0) / (1.0 - f0), 0.0, 1.0);
  });
}

PrincipledTables compute_principled_tables(int n) {
  PrincipledTables tables;
  const int a = kAlbedoSize, s = kInterpolationSize;
  tables.albedo.resize(static_cast<std::size_t>(a * a));
  tables.average_albedo.resize(static_cast<std::size_t>(a));
  tables.interpolation.resize(static_cast<std::size_t>(s * s * s));
  auto saturate = [](double x) { return static_cast<float>(std::clamp(x, 0.0, 1.0)); };
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < a * a; ++i)
    tables.albedo[static_cast<std::size_t>(i)] =
        saturate(ggx_albedo(clamped_axis(i % a, a, 1e-4, 1.0), clamped_axis(i / a, a, 1e-4, 1.0), n));
  tables.schlick_factor.resize(tables.albedo.size());
  tables.f82_factor.resize(tables.albedo.size());
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < a * a; ++i) {
    const double roughness = clamped_axis(i % a, a, 1e-4, 1.0), mu = clamped_axis(i / a, a, 1e-4, 1.0);
    tables.schlick_factor[static_cast<std::size_t>(i)] = saturate(ggx_schlick_factor(roughness, mu, n));
    tables.f82_factor[static_cast<std::size_t>(i)] = saturate(ggx_f82_factor(roughness, mu, n));
  }
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < a; ++i)
    tables.average_albedo[static_cast<std::size_t>(i)] = saturate(ggx_average_albedo(clamped_axis(i, a, 1e-4, 1.0), kAverageCosines, n));
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < s * s * s; ++i)
    tables.interpolation[static_cast<std::size_t>(i)] =
        saturate(ggx_fresnel_interpolation(clamped_axis(i % s, s, 1e-4, 1.0), clamped_axis(i / s % s, s, 1e-4, 1.0),
                                           index_of_axis(clamped_axis(i / (s * s), s, 1e-4, 0.99)), n));
  return tables;
}

std::string principled_tables_source(const PrincipledTables& tables, int n) {
  std::string text =
      "/* Generated by `phongcl-lab principled-tables` (lab/fit/ggx_tables.cpp, each integral on a " +
      std::to_string(n) + " x " + std::to_string(n) +
      "\n * grid of GGX's visible normals): do not edit. The tables Cycles' Principled BSDF v2 reads, at the\n"
      " * points Cycles samples its own (docs/shading.md \"Principled v2\"): row-major, roughness fastest. */\n"
      "#ifndef PHONGCL_PRINCIPLED_TABLES_H\n#define PHONGCL_PRINCIPLED_TABLES_H\n\n"
      "#ifdef __OPENCL_C_VERSION__\n#define PRINCIPLED_TABLE __constant float\n#else\n"
      "#define PRINCIPLED_TABLE static const float\n#endif\n\n"
      "#define GGX_ALBEDO_SIZE " + std::to_string(kAlbedoSize) + "\n#define GGX_INTERPOLATION_SIZE " +
      std::to_string(kInterpolationSize) + "\n\n"
      "/* E(roughness, mu): single-scattering GGX's directional albedo, without Fresnel. */\n";
  append_table(text, "ggx_albedo_table", tables.albedo, kAlbedoSize);
  text += "\n/* E_avg(roughness): 2 mu E(mu) over mu in [0, 1]. */\n";
  append_table(text, "ggx_average_albedo_table", tables.average_albedo, 8);
  text += "\n/* s(roughness, mu, z): the dielectric Fresnel's mean F0-to-1 factor, index (1 + z^2) / (1 - z^2). */\n";
  append_table(text, "ggx_fresnel_interpolation_table", tables.interpolation, kInterpolationSize);
  text += "\n/* The F82-tint metal's mean Fresnel factors over the reflected light, of (1 - f0) and of b. */\n";
  append_table(text, "ggx_schlick_factor_table", tables.schlick_factor, kAlbedoSize);
  append_table(text, "ggx_f82_factor_table", tables.f82_factor, kAlbedoSize);
  text += "\n#endif\n";
  return text;
}

}  // namespace phongcl
