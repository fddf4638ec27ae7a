#include "shading/pack_principled_v2.h"

#include <algorithm>
#include <cmath>

#include "shading/store3.h"

namespace phongcl {

namespace {

double f0_of_index(double ior) {
  const double ratio = (ior - 1.0) / (ior + 1.0);
  return ratio * ratio;
}

// bsdf_util.h, fresnel_dielectric_Fss: Kulla and Conty's fit of the dielectric Fresnel's hemispherical
// mean, 2 c F(c) over c in [0, 1] ("Revisiting physically based shading at Imageworks", 2017).
double fresnel_mean(double eta) {
  if (eta < 1.0) return 0.997118 + eta * (0.1014 - eta * (0.965241 + eta * 0.130607));
  return (eta - 1.0) / (4.08567 + 1.00071 * eta);
}

}  // namespace

bool takes_oren_nayar(const Material& material) {
  return material.specular_model == SpecularModel::principled && material.version == 2 && material.diffuse_roughness >= 1e-5;
}

void store_principled_v2(MaterialRecord& record, const Material& material) {
  const glm::dvec3 base = material.base_color;
  // CLOSURE_WEIGHT_CUTOFF: a metallic weight below it allocates no metal lobe and scales nothing.
  const double metallic = material.metallic > 1e-5 ? material.metallic : 0.0;
  // Specular IOR Level: F0 times twice the level, the index back from it (ior_from_F0 clamps F0 to 0.99).
  double ior = material.ior, f0 = f0_of_index(ior);
  if (material.specular_ior_level != 0.5) {
    f0 *= 2.0 * material.specular_ior_level;
    const double root = std::sqrt(std::clamp(f0, 0.0, 0.99));
    ior = (1.0 + root) / (1.0 - root);
  }
  store3(record.kd, base * (1.0 - metallic));
  store3(record.ks, glm::clamp(f0 * material.specular_tint_color, 0.0, 1.0));
  record.roughness = static_cast<float>(material.roughness);
  record.ior = static_cast<float>(ior);
  // fresnel_f82tint_B: b such that at cos = 1/7 the F82 model is Schlick's times the tint (at most 1).
  const glm::dvec3 metal_f0 = glm::min(base, glm::dvec3(1.0)), edge = glm::min(material.specular_tint_color, glm::dvec3(1.0));
  const double f = 6.0 / 7.0, f5 = std::pow(f, 5.0);
  const glm::dvec3 schlick = metal_f0 + (1.0 - metal_f0) * f5;
  store3(record.metal_f0, metal_f0);
  store3(record.metal_b, edge == glm::dvec3(1.0) ? glm::dvec3(0.0) : schlick * (7.0 / (f5 * f)) * (1.0 - edge));
  record.metal_f0[3] = static_cast<float>(metallic);
  // The dielectric lobe is allocated only where its index is not 1 (in float, as Cycles compares it).
  record.metal_b[3] = record.ior != 1.0f ? 1.0f : 0.0f;
  const double index_f0 = f0_of_index(ior);
  record.fresnel_average = static_cast<float>(std::clamp((fresnel_mean(ior) - index_f0) / (1.0 - index_f0), 0.0, 1.0));
  record.diffuse_roughness = static_cast<float>(takes_oren_nayar(material) ? material.diffuse_roughness : 0.0);
}

}  // namespace phongcl
