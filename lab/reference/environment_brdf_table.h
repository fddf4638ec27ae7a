#pragma once
// The split sum's second factor for the Principled BSDF v1 (Karis 2013; docs/environment.md
// "Specular"): the directional albedo of its GGX lobe under a white world, split by its Fresnel as
// v1 mixes it, (1 - Fh) cspec0 + Fh, into scale A (what cspec0 multiplies) and bias B, over a grid of
// n.v and roughness, by importance sampling the GGX normals. Written out as kernels/environment_brdf.h
// by `phongcl-lab environment-brdf-table`; a test regenerates it and compares.
#include <string>
#include <vector>

namespace phongcl {

// Grid points per axis: n.v = i / (size - 1) (at least 1e-3) and roughness = j / (size - 1).
inline constexpr int kEnvironmentBrdfSize = 32;
// The Fresnel's index: the node's default Specular 0.5 (F0 = 0.04, index 1.5); other values take its
// table (their error is in docs/environment.md).
inline constexpr double kEnvironmentBrdfSpecular = 0.5;

// A and B at (n.v, roughness), for unit n and v and the grid's index: (1/pi) integral of pi BRDF n.l
// over the hemisphere, the BRDF's Fresnel (1 - Fh) + Fh split as above.
struct EnvironmentBrdf {
  double scale = 0.0, bias = 0.0;
};
EnvironmentBrdf environment_brdf(double n_dot_v, double roughness, double specular, int samples_per_axis);

// The table, [n.v][roughness] row by row, scale and bias interleaved.
std::vector<float> environment_brdf_table();

// kernels/environment_brdf.h's text for the table.
std::string environment_brdf_header(const std::vector<float>& table);

}  // namespace phongcl
