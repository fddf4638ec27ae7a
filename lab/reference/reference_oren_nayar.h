// The double reference of Cycles' Oren-Nayar diffuse (kernels/oren_nayar.h; docs/shading.md
// "Oren-Nayar"), derived apart from the kernel: the single scattering's albedos E are integrated over
// the hemisphere (its azimuth in closed form, its elevation numerically), not read from Fujii's G.
#pragma once

#include <glm/vec3.hpp>

namespace phongcl {

// Fujii's single scattering's directional albedo at cosine c in [0, 1] for roughness sigma in [0, 1]:
// the integral of (a + b t) cos over the hemisphere, a = 1 / (pi + sigma (pi/2 - 2/3)), b = sigma a.
double reference_oren_nayar_albedo(double sigma, double c);

// Its mean over the cosine-weighted hemisphere, 2 c E(c) over c in [0, 1].
double reference_oren_nayar_average(double sigma);

// The light Oren-Nayar of roughness sigma and colour `albedo` (each channel in [0, 1]) reflects from a
// light from unit l, per unit Li and over the colour: pi BRDF n.l, single scattering plus OpenPBR's
// multiple scattering Ems (1 - E(n.v)) (1 - E(n.l)). 0 where l is below the horizon.
glm::dvec3 reference_oren_nayar(double sigma, const glm::dvec3& albedo, const glm::dvec3& n, const glm::dvec3& v,
                                const glm::dvec3& l);

// The same over Lambert's n.l, with n.l at least 1e-4 (an area light's centre about the horizon takes
// the limit).
glm::dvec3 reference_oren_nayar_over_lambert(double sigma, const glm::dvec3& albedo, const glm::dvec3& n,
                                             const glm::dvec3& v, const glm::dvec3& l);

// The light it reflects under a uniform white world, over Lambert's, at view cosine mu: E(mu) plus the
// multiple scattering's integral pi Ems (1 - E(mu)) (1 - E_avg).
glm::dvec3 reference_oren_nayar_white_sky(double sigma, const glm::dvec3& albedo, double mu);

}  // namespace phongcl
