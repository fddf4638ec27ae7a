// Principled surfaces (kernels/principled.h; docs/shading.md "Principled" and "Principled v2"), both
// versions, at their inputs' limits: roughness 1, 1e-4 (a mirror: no highlight from a light) and just
// above each version's mirror threshold; IOR 1 and 3 (v2), specular 0 and 1 (v1), metallic 0 and 1,
// base colour 0 and 1; each over the geometry's limits: the highlight's peak, a normal tilted alpha
// and 0.3 rad off it, n.v = 1e-4 and 0, n.l = 1e-4 and 0; under a point light, a sun and a rect. The
// oracle is the double reference's BSDF (reference_principled.h, reference_principled_v2.h; with v2's
// diffuse roughness 1e-5 and 1, Oren-Nayar's, under the point light) with its
// Smith masking integrated per call, not read from the table the reference's shade uses; under the
// rect, Lambert's irradiance and v1's highlight by the reference's quadrature at twice its default order.
#include <algorithm>
#include <cmath>

#include "reference/reference_area.h"
#include "reference/reference_principled_v2.h"
#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {

constexpr int kRectOracleOrder = 96;

enum class Emitter { point, sun, rect };

const char* emitter_name(Emitter emitter) {
  switch (emitter) {
    case Emitter::point: return "point";
    case Emitter::sun: return "sun";
    case Emitter::rect: return "rect";
  }
  return "";
}

// The pixels sit at P = (0, 0, -1), v = (0, 0, 1); the light comes from l = (1, 0, 1) / sqrt 2 (a point
// light at P + (1, 0, 1), a sun travelling along -l, a rect's centre 2 away that way, facing P), so
// that n = (-1, 0, 1) has n.l = 0 exactly in float and in double (its products are equal), and
// n = (1, 0, 0) n.v = 0 exactly.
const glm::vec3 kPosition(0.0f, 0.0f, -1.0f);
const glm::dvec3 kToLight = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));

// The normal at angle `angle` from +z towards +x: the half vector of l and v is at 22.5 degrees.
glm::vec3 in_plane(double angle) { return {static_cast<float>(std::sin(angle)), 0.0f, static_cast<float>(std::cos(angle))}; }

// The normals, in the order `what` names them: the peak, alpha and 0.3 rad off it, n.v = 1e-4 and 0,
// n.l = 1e-4 and 0.
std::vector<glm::vec3> normals(double alpha) {
  const double peak = std::acos(-1.0) / 8.0;
  return {in_plane(peak), in_plane(peak + std::min(alpha, 0.3)), in_plane(peak - 0.3), {1.0f, 0.0f, 1e-4f},
          {1.0f, 0.0f, 0.0f}, {-1.0f + 1e-4f, 0.0f, 1.0f + 1e-4f}, {-1.0f, 0.0f, 1.0f}};
}

Material principled(int version, double base, double metallic, double roughness) {
  Material m;
  m.name = "principled";
  m.specular_model = SpecularModel::principled;
  m.version = version;
  m.base_color = glm::dvec3(base);
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

AreaLight facing_rect() {
  AreaLight light;
  light.shape = AreaShape::rect;
  light.position = glm::dvec3(kPosition) + 2.0 * kToLight;
  light.direction = -kToLight;
  light.up = {0.0, 1.0, 0.0};
  light.size = {0.6, 0.4};
  return light;
}

// The oracle's light at one pixel, per unit light colour.
glm::dvec3 oracle(const Material& m, Emitter emitter, const AreaLight& rect, const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 v = glm::normalize(-p);
  if (emitter != Emitter::rect) {
    const PrincipledLight light = reference_principled_of_version(m, n, v, kToLight);
    return light.diffuse + light.specular;
  }
  const double irradiance = reference_area_integrals(rect, p, n, v, SpecularModel::phong, 1.0, kRectOracleOrder).irradiance;
  const glm::dvec3 weight = m.version == 2 ? reference_principled_v2_lambert(m, std::clamp(glm::dot(n, v), 0.0, 1.0)) *
                                                 reference_principled_v2_over_lambert(m, n, v, kToLight)
                                           : m.base_color * (1.0 - m.metallic);
  glm::dvec3 value = weight * irradiance;
  return value + reference_principled_area(m, rect, p, n, v);
}

// One pixel per material and geometry, under one white light.
StabilityCase principled_case(int version, Emitter emitter, const std::string& label, const std::string& limits,
                              const std::vector<Material>& materials) {
  StabilityCase c;
  c.group = "principled";
  c.name = "principled v" + std::to_string(version) + " " + emitter_name(emitter) + " " + label;
  c.scene.camera.eye = {0.0, 0.0, 0.0};
  c.scene.materials = materials;
  const AreaLight rect = facing_rect();
  if (emitter == Emitter::point)
    c.scene.lights.push_back({LightType::point, glm::dvec3(kPosition) + glm::dvec3(1.0, 0.0, 1.0), {}, {1.0, 1.0, 1.0}});
  if (emitter == Emitter::sun) c.scene.lights.push_back({LightType::directional, {}, -kToLight, {1.0, 1.0, 1.0}});
  if (emitter == Emitter::rect) c.scene.area_lights.push_back(rect);
  std::size_t pixels = 0;
  for (const Material& m : materials) pixels += normals(m.roughness * m.roughness).size();
  c.gbuffer = blank_gbuffer(static_cast<int>(pixels), 1, c.name);
  std::size_t i = 0;
  for (std::size_t k = 0; k < materials.size(); ++k)
    for (const glm::vec3& normal : normals(materials[k].roughness * materials[k].roughness))
      set_surface(c.gbuffer, i++, kPosition, normal, static_cast<float>(k));
  c.oracle = [materials, emitter, rect] {
    std::vector<ExactColor> values;
    for (const Material& m : materials)
      for (const glm::vec3& normal : normals(m.roughness * m.roughness)) {
        const glm::dvec3 value = oracle(m, emitter, rect, glm::dvec3(kPosition), glm::normalize(glm::dvec3(normal)));
        values.push_back({value.r, value.g, value.b});
      }
    return values;
  };
  c.what = std::to_string(materials.size()) + " materials x 7 normals (peak, alpha and 0.3 off, n.v = 1e-4 and 0, "
           "n.l = 1e-4 and 0): " + limits;
  // n.l and n.v are dot products of unit float vectors, each off by a few float units (6e-8)
  // absolutely: at n.l = 0 (measured 2.3e-8, where an fma keeps a product's rounding) that is the
  // whole value, and every response is O(1) per unit n.l. Against 1e-6 that alone reads 2e-2.
  c.abs_floor = 1e-4;
  return c;
}

// The bounds, each from what limits the variant at these inputs; the measured worst errors (PoCL 3.1
// on the CPU, 2026-12-07) are in the text.
StabilityCase with_bounds(StabilityCase c, int version, Emitter emitter, bool roughness_limits) {
  using E = Expectation;
  // Under a point light or a sun: n.l = 1e-4 is a dot product of components near 0.7, whose absolute
  // rounding (~6e-8) is 6e-4 of it; the value there is proportional to n.l.
  const E grazing_light = E::within(1e-3, "n.l = 1e-4 from components near 0.7: a few 6e-8 of absolute rounding, 3.3e-4 "
                                          "measured against the 1e-4 floor");
  const E half_lost = E::finite_only("normals rounded to half (2^-11): n.l = 1e-4 becomes 0 (relative error 1 measured) "
                                     "and a normal alpha off the sharpest lobe's peak moves by more than alpha");
  // Version 2 reads E, E_avg and s from tables (kernels/principled_tables.h) that the reference
  // integrates its own way: 5.2e-4 apart at cosines 0.02 to 1 (docs/shading.md), 1.1e-3 measured at n.v = 0.
  const E tables = E::within(3e-3, "v2's GGX tables against the reference's quadrature: 1.1e-3 measured at n.v = 0");
  if (emitter == Emitter::rect && version == 1) {
    // The highlight is the LTC fit's (docs/shading.md "Principled under area lights"), and the kernel's
    // LTC has no mirror threshold: roughness 1e-4 takes the lobe fitted at 0.02, where the reference
    // has no highlight.
    const E fit = E::finite_only("the LTC fit's highlight, with no mirror threshold: 2.9 measured at roughness 1e-4");
    c.expect = {fit, fit, fit, fit};
    return c;
  }
  if (emitter == Emitter::rect && !roughness_limits) {
    // Version 2's highlight is version 1's LTC coloured by its own lobe: at n.l = 1e-4 the emitter,
    // clipped to the horizon, leaves the LTC nothing where the reference integrates 4.3e-4 of a light
    // whose peak is 0.26.
    const E grazing = E::finite_only("the LTC's highlight at n.l = 1e-4: 0 against the reference's 4.3e-4 (relative 1)");
    c.expect = {grazing, grazing, grazing, grazing};
    return c;
  }
  if (emitter == Emitter::rect) {
    c.expect = {tables, tables, tables,
                E::within(5e-3, "normals rounded to half move Lambert's E by its derivative: 1.35e-3 measured, with the "
                                "tables' 1.1e-3")};
    return c;
  }
  if (version == 1) {
    const E double_bound = emitter == Emitter::sun && roughness_limits
                               ? E::within(1e-4, "the sun's direction packed as float (2^-24) times the sharpest lobe's "
                                                 "slope 2 / alpha = 5e3: 1.8e-5 measured")
                               : E::within(2e-6, "float result rounding and packing: 5.4e-7 measured");
    c.expect = {double_bound, grazing_light, grazing_light, half_lost};
    c.reference = roughness_limits
                      ? E::finite_only("the reference's shade reads Smith's G1 from 4097 nodes in mu, linear between them: "
                                       "at n.v = 1e-4 on the alpha = 4e-4 metal, between G1(0) = 0 and G1(2.4e-4), "
                                       "0.28 low (measured)")
                      : E::within(2e-3, "the reference's tabulated G1 at n.v = 1e-4: 5.8e-4 measured");
    return c;
  }
  const E sharpest = E::within(5e-3, "direction rounding (~1e-7 rad) times the sharpest lobe's slope 2 / alpha = 1.25e5 "
                                     "alpha off its peak: 1.9e-3 measured, with the tables' 1.1e-3");
  c.expect = {tables, roughness_limits ? sharpest : tables, roughness_limits ? sharpest : tables, half_lost};
  c.reference = roughness_limits ? E::within(1e-2, "the reference's tabulated G1 at n.v = 1e-4 on the alpha = 1.6e-5 metal, "
                                                  "whose light there (7e-7) is below the floor: 4.1e-3 measured")
                                 : E::within(2e-3, "the reference's tabulated G1 at n.v = 1e-4: 5.8e-4 measured");
  return c;
}

std::vector<Material> roughness_limits(int version, bool with_sharpest) {
  std::vector<Material> materials = {principled(version, 0.8, 0.0, 1.0), principled(version, 0.8, 0.0, 1e-4)};
  // Just above the mirror threshold: v1's alpha^2 > 1e-7, v2's > 2e-10 (kernels/principled.h). Not
  // under v1's rect: the quadrature of a lobe 4e-4 wide over the emitter takes 0.7 s, for a
  // highlight that is finite only there.
  const double sharpest = version == 1 ? 0.02 : 0.004;
  if (with_sharpest) {
    materials.push_back(principled(version, 0.8, 0.0, sharpest));
    materials.push_back(principled(version, 0.8, 1.0, sharpest));
  }
  return materials;
}

std::vector<Material> fresnel_and_colour_limits(int version) {
  std::vector<Material> materials = {principled(version, 1.0, 1.0, 0.5), principled(version, 0.0, 0.0, 0.5),
                                     principled(version, 1.0, 0.0, 0.5), principled(version, 0.0, 1.0, 0.5)};
  for (double edge : {0.0, 1.0}) {
    Material m = principled(version, 0.8, 0.0, 0.5);
    if (version == 1) m.specular = edge;         // 0: no Fresnel (index 1); 1: F0 = 0.08
    if (version == 2) m.ior = edge == 0.0 ? 1.0 : 3.0;  // 1: no dielectric layer
    materials.push_back(m);
  }
  return materials;
}

// Version 2's Oren-Nayar at its limits: Cycles' threshold 1e-5, where 1 - E is 2e-6 of an E near 1
// (float's resolution of 1 is 6e-8), and 1; a white base (the multiple scattering's largest) and a grey one.
std::vector<Material> diffuse_roughness_limits() {
  std::vector<Material> materials;
  for (double sigma : {1e-5, 1.0})
    for (double base : {1.0, 0.5}) {
      Material m = principled(2, base, 0.0, 0.5);
      m.diffuse_roughness = sigma;
      materials.push_back(m);
    }
  return materials;
}

}  // namespace

std::vector<StabilityCase> principled_cases() {
  std::vector<StabilityCase> cases;
  for (int version : {1, 2}) {
    for (Emitter emitter : {Emitter::point, Emitter::sun, Emitter::rect}) {
      const bool sharpest = version == 2 || emitter != Emitter::rect;
      cases.push_back(with_bounds(principled_case(version, emitter, "roughness",
                                                  sharpest ? "roughness 1, 1e-4 (a mirror) and just above the mirror "
                                                             "threshold, dielectric and metal"
                                                           : "roughness 1 and 1e-4 (a mirror)",
                                                  roughness_limits(version, sharpest)),
                                  version, emitter, true));
      // Not under v1's rect: its highlight there is the LTC fit's, finite only, whose error
      // test_area_lights measures.
      if (version == 1 && emitter == Emitter::rect) continue;
      cases.push_back(with_bounds(principled_case(version, emitter, "Fresnel and colour",
                                                  version == 1 ? "specular 0 and 1, metallic 0 and 1, base 0 and 1"
                                                               : "IOR 1 and 3, metallic 0 and 1, base 0 and 1",
                                                  fresnel_and_colour_limits(version)),
                                  version, emitter, false));
    }
  }
  cases.push_back(with_bounds(principled_case(2, Emitter::point, "diffuse roughness",
                                              "diffuse roughness 1e-5 (Cycles' threshold) and 1, base 1 and 0.5",
                                              diffuse_roughness_limits()),
                              2, Emitter::point, false));
  return cases;
}

}  // namespace phongcl
