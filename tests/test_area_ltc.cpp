// Principled (GGX) highlights under rect and disk area lights by linearly transformed cosines
// (kernels/area_ltc.h, docs/shading.md "Principled under area lights"): the fit's lobe is the
// reference's BSDF, and the kernel's highlight against the reference's BSDF integrated over the
// emitter, per roughness, for a metal and a dielectric (whose light is mostly Fresnel's).
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "area_test_scenes.h"
#include "fit/ggx_lobe.h"
#include "reference/reference.h"
#include "reference/reference_principled.h"
#include "shading_support.h"

namespace phongcl {
namespace {

using testing::area_scene;
using testing::AreaScene;
using testing::emitters;
using testing::term_error;
using testing::TermError;

// The masking table read between its nodes against the reference's numerical G1, and so the fit's
// lobe against reference_principled on a white metal, over random directions and roughness 0.05 to 1.
TEST(LtcFit, TheFittedLobeIsTheReferencesBsdf) {
  std::mt19937 rng(4601);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zero_one(0.0, 1.0);
  for (double roughness : {0.05, 0.2, 0.5, 1.0}) {
    const GgxLobe lobe(roughness);
    Material metal;
    metal.specular_model = SpecularModel::principled;
    metal.base_color = glm::dvec3(1.0);
    metal.metallic = 1.0;
    metal.roughness = roughness;
    for (int k = 0; k < 50; ++k) {
      const glm::dvec3 v = glm::normalize(glm::dvec3(unit(rng), unit(rng), 0.05 + zero_one(rng)));
      const glm::dvec3 l = glm::normalize(glm::dvec3(unit(rng), unit(rng), 0.05 + zero_one(rng)));
      const double exact = reference_principled(metal, glm::dvec3(0, 0, 1), v, l).specular.x;
      // 4097 nodes: linear interpolation of G1 is within 1e-6 relative where n.v, n.l >= 0.05
      EXPECT_NEAR(lobe.value(v, l), exact, 2e-6 * exact) << "roughness " << roughness << ", v.z " << v.z << ", l.z " << l.z;
    }
  }
}

// Measured worst (docs/shading.md): median 3.0e-2 over every lit pixel (rects, metal, roughness 0.3: the
// faint tails, where one direction's correction stands for the emitter's), 2.1e-2 over the highlight
// (rects, dielectric, roughness 0.6); without the tail correction they were 9.7e-2 and 4.9e-2.
constexpr double kMedianBound = 0.05, kHighlightBound = 0.035;

// The median relative error of channel 0 on the pixels whose reference is at least `fraction` of the
// image's largest: where the highlight is, apart from its faint tail.
double bright_median(const Image& kernel, const Image& reference, double fraction) {
  double largest = 0.0;
  for (std::size_t i = 0; i < reference.pixel_count(); ++i) largest = std::max(largest, double(reference.pixel(i)[0]));
  std::vector<double> errors;
  for (std::size_t i = 0; i < reference.pixel_count(); ++i) {
    const double want = reference.pixel(i)[0];
    if (want >= fraction * largest && want > 0.0) errors.push_back(std::abs(kernel.pixel(i)[0] - want) / want);
  }
  if (errors.empty()) return 0.0;
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

// Each lane's specular light (ambient 0, the diffuse weight 0: a black dielectric, whose light is
// mostly Fresnel's, and a grey metal) against the reference over area_scene's points, many of them
// seen at grazing angles and with the emitter cut by their horizon. The LTC is a fit: the bounds are
// its measured error (docs/shading.md) with room, per roughness, not rounding bounds; a wrong frame,
// skew sign, magnitude or Fresnel is off by far more. Printed: the median over every lit pixel and over
// the highlight (>= 10% of the largest), and the worst pixel. One version at each roughness.
void expect_highlights_match(PhongShader& shader, int version, std::initializer_list<double> roughnesses) {
  for (bool rect : {true, false})
    for (bool metal : {true, false})
      for (double roughness : roughnesses) {
        AreaScene s = area_scene(emitters(rect), glm::dvec3(1.0), 1.0, rect ? 4701 : 4702);
        Material& m = s.scene.materials[0];
        m.specular_model = SpecularModel::principled;
        m.version = version;
        m.base_color = glm::dvec3(metal ? 0.9 : 0.0);
        m.metallic = metal ? 1.0 : 0.0;
        m.roughness = roughness;
        m.specular = 0.5;
        m.specular_tint_color = version == 2 ? glm::dvec3(1.0, 0.8, 0.6) : glm::dvec3(1.0);
        const Image reference = reference_image(s.scene, s.gbuffer);
        const Image shaded = shader.shade(s.scene, s.gbuffer, ShadeOptions{}).image;
        const TermError error = term_error(shaded, reference);
        const double bright = bright_median(shaded, reference, 0.1);
        std::ostringstream label;
        label << "v" << version << (rect ? " rects" : " disks") << (metal ? ", metal" : ", dielectric") << ", roughness "
              << roughness;
        const std::string name = label.str();
        std::cout << name << ": specular against the reference, " << error.lit << " lit pixels, median " << error.median_rel
                  << ", highlight median " << bright << ", max " << error.max_rel << " (pixel " << error.worst << ": "
                  << error.worst_kernel << " for " << error.worst_reference << ")\n";
        EXPECT_GT(error.lit, s.gbuffer.pixel_count() / 8);
        EXPECT_LE(error.median_rel, kMedianBound) << name;
        EXPECT_LE(bright, kHighlightBound) << name;
      }
}

TEST(AreaLtc, PrincipledHighlightMatchesTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  expect_highlights_match(shader, 1, {0.15, 0.3, 0.6, 1.0});
}

// Version 2 (a metal of F82 tint (1, 0.8, 0.6), a dielectric of ior 1.5) takes the same LTC coloured
// by its lobe over version 1's white one at the light's mean direction (ltc_v2_tint): the same bounds
// (measured worst: median 3.0% at roughness 0.3, highlight median 2.4% at 1), at the roughness where
// version 1's figures are worst. A test of its own: the reference's integrals take minutes under ASan.
TEST(AreaLtc, PrincipledV2HighlightMatchesTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  expect_highlights_match(shader, 2, {0.3, 1.0});
}

}  // namespace
}  // namespace phongcl
