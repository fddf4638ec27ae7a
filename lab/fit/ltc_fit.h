// Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016) fitted to Cycles 3.x's
// Principled (v1) GGX lobe without Fresnel (ggx_lobe.h), over the node's roughness and the view's
// cosine. The kernel (kernels/area_ltc.h) reads the table `phongcl-lab fit-ltc` writes
// (kernels/ltc_table.h); docs/shading.md "Principled under area lights" states its error.
#pragma once

#include <filesystem>
#include <vector>

#include <glm/mat3x3.hpp>

namespace phongcl {

// The table's axes: roughness i / (size - 1), fitted no lower than ltc_roughness_min (below, GGX is a
// near mirror whose fit the table's float entries cannot hold); view coordinate j / (size - 1) =
// sqrt(1 - cos), fitted no lower in cosine than ltc_cos_view_min.
inline constexpr double ltc_roughness_min = 0.02, ltc_cos_view_min = 0.02;
double ltc_node_roughness(int i, int size);
double ltc_node_cos_view(int j, int size);

struct LtcEntry {
  double roughness = 0.0, cos_view = 0.0;  // where it was fitted
  // M^-1 over its (1, 1) entry, in the frame x towards v, z = n: the lobe is D_o(M^-1 w / |M^-1 w|)
  // |det M^-1| / |M^-1 w|^3 times `magnitude`, D_o = max(0, z) / pi.
  glm::dmat3 inverse{1.0};
  double magnitude = 0.0;  // the lobe's integral over the hemisphere / pi: its albedo without Fresnel
  double l3_error = 0.0;   // the fit's objective: the integral of |lobe - LTC|^3, both normalised to 1
  double l1_error = 0.0;   // the integral of |lobe - LTC|, both normalised to 1 (0: equal; 2: disjoint)
};

// The fit over a size x size grid, entry [i * size + j] at roughness node i and view node j, each by
// Nelder-Mead on the L3 error from the neighbour fitted before it (rough to smooth, normal to grazing).
std::vector<LtcEntry> fit_ltc_table(int size);

// The table as an OpenCL C header, with its error in its opening comment.
void write_ltc_header(const std::vector<LtcEntry>& table, int size, const std::filesystem::path& file);

}  // namespace phongcl
