// The double reference of the Principled BSDF v2 (kernels/principled.h; docs/shading.md "Principled
// v2"), derived apart from the kernel: GGX's density from its slopes, height-correlated masking from
// Smith's Lambda integrated over the slopes, the dielectric Fresnel from Snell's law, and the albedos
// the energy compensation and the layering need integrated over GGX's normal distribution (the lab's
// tables integrate over its visible normals) at the points Cycles tabulates them, interpolated as
// Cycles reads its tables.
#pragma once

#include <functional>

#include <glm/vec3.hpp>

#include "reference/reference_principled.h"
#include "scene/scene.h"

namespace phongcl {

// A light's diffuse and specular light on a version 2 surface, per unit Li: pi BRDF n.l for unit n, v, l.
PrincipledLight reference_principled_v2(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                        const glm::dvec3& l);

// The light of the material's own version: reference_principled_v2 or, for version 1, reference_principled.
PrincipledLight reference_principled_of_version(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                const glm::dvec3& l);
// The same with Smith's masking G1 given as a function of the cosine (for the material's alpha).
PrincipledLight reference_principled_v2(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                        const glm::dvec3& l, const std::function<double(double)>& masking);
PrincipledLight reference_principled_of_version(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                const glm::dvec3& l, const std::function<double(double)>& masking);
// Its specular light alone, for the integrals over emitters and texels.
glm::dvec3 reference_principled_specular_of_version(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                    const glm::dvec3& l, const std::function<double(double)>& masking);

// The share of Lambert's light (area lights', the environment's) the diffuse beneath the dielectric
// layer takes at view cosine mu, times base colour and 1 - metallic.
glm::dvec3 reference_principled_v2_lambert(const Material& material, double mu);

// What the diffuse reflects over Lambert: 1, or where Diffuse Roughness is at least 1e-5 (Cycles'
// threshold) Oren-Nayar's response over Lambert's from unit l (an area light's centre) ...
glm::dvec3 reference_principled_v2_over_lambert(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                                const glm::dvec3& l);
// ... and under a uniform white world at view cosine mu (the environment's).
glm::dvec3 reference_principled_v2_white_sky(const Material& material, double mu);

// GGX's albedos at alpha = roughness^2 and view cosine mu: single scattering without Fresnel (E), and the
// mean of the dielectric Fresnel's [F0, 1] factor over the reflected light (s) for index eta.
struct GgxAlbedos {
  double albedo = 0.0, fresnel_factor = 0.0;
};
GgxAlbedos reference_ggx_albedos(double alpha, double mu, double eta);

}  // namespace phongcl
