#pragma once
// The environment's specular light, precomputed (docs/environment.md "Specular"): the map without
// its suns convolved with a lobe symmetric about the reflected direction r, one small equirect map
// per distinct lobe of the scene. The Phong lobe max(0, r.w)^p is symmetric about r, so its map is
// exact up to the grid; Blinn-Phong takes its equivalent Phong exponent p = q / 4, and GGX the lobe
// of Karis' split sum (n = v = r). The kernel reads it bilinearly (kernels/environment_specular.h).
#include <memory>

#include <glm/glm.hpp>

#include "environment/equirect_map.h"
#include "environment/irradiance_map.h"

namespace phongcl {

// A lobe as a function of c = r.w > 0 (0 for c <= 0): Phong's c^q; Blinn-Phong's (n.h)^q at normal
// incidence, ((1 + c) / 2)^(q / 2); times c where `takes_cosine` (the normalised models' n.l, which
// is n.r c plus a part odd about r). GGX's is D(h) c with h halfway between r and w (n.h = sqrt((1 +
// c) / 2)) for alpha = roughness^2: the weight of a direction w in Karis' prefiltered map, D's
// density of the half vector turned into w's (1 / 4 with n = v) times n.l (takes_cosine is true).
struct SpecularLobe {
  enum class Kind { phong, blinn, ggx };
  Kind kind = Kind::phong;
  double parameter = 1.0;  // the exponent q, or GGX's alpha
  bool takes_cosine = false;

  bool operator==(const SpecularLobe&) const = default;
  auto operator<=>(const SpecularLobe&) const = default;
};

// The lobe's weight at c = r.w, unnormalised (its peak is at c = 1).
double lobe_weight(const SpecularLobe& lobe, double c);

// (1/pi) times the lobe's integral over the hemisphere about r, 2 integral_0^1 weight(c) dc (closed
// forms): what a white world gives it, and what its mean radiance is multiplied by. 1 for GGX, whose
// integral (with its masking and Fresnel) is the split sum's table.
double lobe_integral(const SpecularLobe& lobe);

// The lobe's width: the angle from r at which its weight falls to exp(-1/2) of the peak (a
// Gaussian's standard deviation).
double lobe_width(const SpecularLobe& lobe);

// The prefiltered map's rows: texels at most half the lobe's width apart (2 pi / width rows, a power
// of two from 4), up to the radiance grid's kRadianceGridHeight; twice as many columns.
int prefiltered_height(const SpecularLobe& lobe);

// The lobe-weighted mean radiance about `r` (unit, the map's frame): sum L(w) K(r.w) dw / sum K(r.w) dw
// over the grid's cells, each a direction at its centre with its solid angle; the cells whose
// weight is under 1e-6 of the peak are left out of both sums.
glm::dvec3 prefiltered_radiance(const RadianceGrid& radiance, const SpecularLobe& lobe, const glm::dvec3& r);

// prefiltered_radiance at the centre of every texel of a prefiltered_height(lobe) map. A 1 x 1 grid
// (a uniform world) is its own prefiltered map.
RadianceGrid prefilter(const RadianceGrid& radiance, const SpecularLobe& lobe);

// prefilter of the map's radiance without its suns, computed once per map and lobe and kept while the
// map is (maps of files are kept for the process).
std::shared_ptr<const RadianceGrid> prefiltered_of(const std::shared_ptr<const IrradianceMap>& map, const SpecularLobe& lobe);

}  // namespace phongcl
