// The tables Cycles' Principled BSDF v2 reads (docs/shading.md "Principled v2"), computed here by
// integrating the GGX BRDF, never copied: the directional albedo E(roughness, mu) of single-scattering
// GGX without Fresnel, its cosine-weighted average E_avg(roughness), and the F0-to-1 interpolation
// factor s(roughness, mu, z) that the real dielectric Fresnel gives on average over the reflected light,
// and the two factors of the F82-tint metal's Fresnel (the environment's split sum reads those).
// Each is an average over the GGX distribution of visible normals (Heitz 2018), taken on an n x n
// midpoint grid of that distribution's disk parameters, at the grid points Cycles samples its own
// (roughness = x / (nx - 1), mu = y / (ny - 1), z = k / (nz - 1), each clamped as Cycles does).
#pragma once

#include <string>
#include <vector>

namespace phongcl {

inline constexpr int kAlbedoSize = 32;      // E: 32 roughnesses x 32 cosines; E_avg: 32 roughnesses
inline constexpr int kInterpolationSize = 16;  // s: 16 roughnesses x 16 cosines x 16 indices
inline constexpr int kAverageCosines = 128;    // E_avg's midpoints in mu (its integrand is smooth there)

// The index whose normal-incidence reflectance is z^4: the table's third axis (most entries at 1 to 2).
double index_of_axis(double z);

// E at (roughness, mu): the share of light single-scattering GGX reflects (no Fresnel), on an n x n grid.
double ggx_albedo(double roughness, double mu, int n);
// E_avg at roughness: 2 mu E(mu) integrated over mu in [0, 1] (midpoints), each E on an n x n grid.
double ggx_average_albedo(double roughness, int mu_points, int n);
// s at (roughness, mu, index): the visible normals' mean of (F(h.v) - F0) / (1 - F0), F the dielectric's
// Fresnel, counting 0 where the reflected direction falls below the horizon.
double ggx_fresnel_interpolation(double roughness, double mu, double index, int n);

// The F82-tint Fresnel's mean factors over the light single-scattering GGX reflects, weighted as E
// integrates it: of (1 - f0) in (1 - h.v)^5, and of b in h.v (1 - h.v)^6. The metal's albedo is
// E (f0 + (1 - f0) schlick - b f82).
double ggx_schlick_factor(double roughness, double mu, int n);
double ggx_f82_factor(double roughness, double mu, int n);

struct PrincipledTables {
  std::vector<float> albedo;          // [mu][roughness], kAlbedoSize^2
  std::vector<float> average_albedo;  // [roughness], kAlbedoSize
  std::vector<float> interpolation;   // [z][mu][roughness], kInterpolationSize^3
  std::vector<float> schlick_factor;  // [mu][roughness], kAlbedoSize^2
  std::vector<float> f82_factor;      // [mu][roughness], kAlbedoSize^2
};

// Every entry, each integral on an n x n grid (E_avg over kAverageCosines cosines).
PrincipledTables compute_principled_tables(int n);

// kernels/principled_tables.h's text: the tables as OpenCL C (and C++) constant arrays.
std::string principled_tables_source(const PrincipledTables& tables, int n);

}  // namespace phongcl
