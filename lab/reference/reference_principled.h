// The double reference of the Principled BSDF v1 (kernels/principled.h; docs/shading.md "Principled"),
// derived apart from the kernel's formulas: GGX's normal density from its slope distribution, Smith's
// masking by integrating that distribution numerically, the Fresnel from Snell's law and the amplitude
// coefficients, Burley's diffuse from its half-angle form.
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace phongcl {

// A light's diffuse and specular light on a Principled surface, per unit Li (phongcl's light colour,
// 1/pi folded in): pi BRDF n.l for unit n, v, l. The diffuse includes the base colour and 1 - metallic.
struct PrincipledLight {
  glm::dvec3 diffuse{0.0}, specular{0.0};
};
PrincipledLight reference_principled(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                     const glm::dvec3& l);

// Smith's masking G1 for GGX of roughness alpha at cosine mu > 0, 1 / (1 + Lambda), Lambda integrated
// numerically over the distribution's slopes (Heitz 2014, "Understanding the masking-shadowing
// function", eq. 72).
double reference_smith_masking(double alpha, double mu);

// The unpolarised reflectance of a dielectric of relative index eta at incidence cosine c.
double reference_dielectric_fresnel(double c, double eta);

}  // namespace phongcl
