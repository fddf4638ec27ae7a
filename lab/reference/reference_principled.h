// The double reference of the Principled BSDF v1 (kernels/principled.h; docs/shading.md "Principled"),
// derived apart from the kernel's formulas: GGX's normal density from its slope distribution, Smith's
// masking by integrating that distribution numerically, the Fresnel from Snell's law and the amplitude
// coefficients, Burley's diffuse from its half-angle form.
#pragma once

#include <functional>
#include <vector>

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
// The same with Smith's masking G1 given as a function of the cosine (for the material's alpha).
PrincipledLight reference_principled(const Material& material, const glm::dvec3& n, const glm::dvec3& v,
                                     const glm::dvec3& l, const std::function<double(double)>& masking);

// GGX's normal density of roughness alpha at cosine c to the normal, from its slope distribution.
double reference_ggx_density(double alpha, double c);

// The specular light of a Principled surface (either version) from an area light per unit Li, without
// the range window: the BSDF integrated over the emitter (reference_area.h's rules). 0 for alpha^2 <=
// 1e-7, as reference_principled's.
glm::dvec3 reference_principled_area(const Material& material, const AreaLight& light, const glm::dvec3& position,
                                     const glm::dvec3& n, const glm::dvec3& v);

// Smith's masking G1 for GGX of roughness alpha at cosine mu > 0, 1 / (1 + Lambda), Lambda integrated
// numerically over the distribution's slopes (Heitz 2014, "Understanding the masking-shadowing
// function", eq. 72).
double reference_smith_masking(double alpha, double mu);

// reference_smith_masking for one alpha, read linearly between 4097 nodes in mu (within 1e-6 of it:
// test_ltc_fit): for integrals over directions, which call the BSDF millions of times.
class SmithMaskingTable {
 public:
  explicit SmithMaskingTable(double alpha);
  double operator()(double mu) const;

 private:
  std::vector<double> nodes_;  // G1 at mu = k / (size - 1)
};
// The table of one alpha, made once per thread.
const SmithMaskingTable& smith_masking_table(double alpha);

// The unpolarised reflectance of a dielectric of relative index eta at incidence cosine c.
double reference_dielectric_fresnel(double c, double eta);

}  // namespace phongcl
