// The specular models (docs/shading.md "Specular models"): each against the double reference in
// every precision variant but half-storage, one model and mixed, table and per-pixel materials;
// what reaches the recipe; and the normalised lobes' directional albedo, by quadrature of the
// reference's lobe.
#include <algorithm>
#include <cmath>

#include "reference/reference.h"
#include "shading_support.h"

namespace phongcl {
namespace {

using testing::describe_worst;
using testing::kRelativeBound;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;

constexpr double kPi = 3.14159265358979323846;

unsigned mask_of(const std::vector<SpecularModel>& models) {
  unsigned mask = 0;
  for (SpecularModel model : models) mask |= 1u << static_cast<int>(model);
  return mask;
}

// A random scene (shininess up to 1000, normals of any length) whose materials take `models` in
// turn; per_pixel: kd, ks and q per pixel, ka from the table (which so gives the model).
std::pair<Scene, GBuffer> scene_with_models(const std::vector<SpecularModel>& models, unsigned seed, bool per_pixel) {
  RandomSceneSpec spec;
  spec.per_pixel_materials = per_pixel;
  auto [scene, gbuffer] = random_scene(spec, seed);
  for (Plane& plane : gbuffer.ka) plane.clear();
  for (std::size_t i = 0; i < scene.materials.size(); ++i) scene.materials[i].specular_model = models[i % models.size()];
  return {scene, gbuffer};
}

const std::vector<std::vector<SpecularModel>> kModelSets = {
    {SpecularModel::phong_normalized},
    {SpecularModel::blinn_phong},
    {SpecularModel::blinn_phong_normalized},
    {SpecularModel::phong, SpecularModel::phong_normalized, SpecularModel::blinn_phong, SpecularModel::blinn_phong_normalized},
    {SpecularModel::blinn_phong_normalized, SpecularModel::phong},
};

std::string names(const std::vector<SpecularModel>& models) {
  std::string text;
  for (SpecularModel model : models) text.append(text.empty() ? "" : "+").append(to_string(model));
  return text;
}

// The product's bound holds for every lobe: the half vector adds s = l + v (one rounding per
// component), its rsqrt and n - h (one more), the same chain as Phong's w and v - r.
TEST(Specular, EachModelMatchesTheReferenceInEveryVariantAndLaneCount) {
  PHONGCL_REQUIRE_DEVICE(shader);
  unsigned seed = 4400;
  for (const auto& models : kModelSets) {
    for (bool per_pixel : {false, true}) {
      for (Precision precision : {Precision::precise, Precision::fast, Precision::double_precision}) {
        if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
        for (int lanes : {1, 16}) {
          const auto [scene, gbuffer] = scene_with_models(models, ++seed, per_pixel);
          ShadeOptions options;
          options.precision = precision;
          options.lanes = lanes;
          const ShadeResult result = shader.shade(scene, gbuffer, options);
          EXPECT_EQ(result.recipe.value("SPECULAR_MODELS"), std::to_string(mask_of(models))) << result.build_options;
          testing::expect_background_exact(result.image, scene, gbuffer);
          const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
          EXPECT_EQ(stats.nonfinite_mismatches, 0u) << names(models);
          EXPECT_LE(stats.max_rel, kRelativeBound) << names(models) << (per_pixel ? ", per-pixel" : ", table") << ", "
                                                   << to_string(precision) << ", " << lanes << " lanes: " << describe_worst(stats);
        }
      }
    }
  }
}

// The general kernel takes the models from the scene too, and agrees with the specialised one.
TEST(Specular, TheGeneralKernelShadesTheSameModels) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto [scene, gbuffer] = scene_with_models(kModelSets[3], 71, false);
  ShadeOptions general;
  general.specialise = false;
  const ShadeResult unspecialised = shader.shade(scene, gbuffer, general);
  EXPECT_EQ(unspecialised.recipe.value("SPECULAR_MODELS"), "15") << unspecialised.build_options;
  const ErrorStats stats = shading_error(unspecialised.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
  EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
}

// The model changes the image: a kernel that ignored it would fail here even where the reference
// were wrong the same way.
TEST(Specular, EveryModelGivesItsOwnImage) {
  PHONGCL_REQUIRE_DEVICE(shader);
  std::vector<Image> images;
  for (SpecularModel model : kSpecularModels) {
    auto [scene, gbuffer] = scene_with_models({model}, 5, false);
    images.push_back(shader.shade(scene, gbuffer, {}).image);
  }
  for (std::size_t a = 0; a < images.size(); ++a)
    for (std::size_t b = a + 1; b < images.size(); ++b)
      EXPECT_NE(images[a].rgba, images[b].rgba) << to_string(kSpecularModels[a]) << " vs " << to_string(kSpecularModels[b]);
}

// A G-buffer that carries every coefficient does not consult the table: phong, as the reference.
TEST(Specular, AGbufferWithEveryCoefficientShadesPhong) {
  PHONGCL_REQUIRE_DEVICE(shader);
  RandomSceneSpec spec;
  spec.per_pixel_materials = true;
  auto [scene, gbuffer] = random_scene(spec, 12);
  for (Material& m : scene.materials) m.specular_model = SpecularModel::blinn_phong_normalized;
  const ShadeResult result = shader.shade(scene, gbuffer, {});
  EXPECT_EQ(result.recipe.value("SPECULAR_MODELS"), "1") << result.build_options;
  const ErrorStats stats = shading_error(result.image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
  EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
  for (Material& m : scene.materials) m.specular_model = SpecularModel::phong;
  EXPECT_EQ(shader.shade(scene, gbuffer, {}).image.rgba, result.image.rgba);
}

// The light loop leaves the specular power out where every lane's cosine is below
// highlight_cutoff(q) (kernels/phong_math.h), whose power is 0 after the flush below 2^-126. Here
// every pixel is just above that flush: n = l = +z, so r = n and v.r = v.z, which the pixels'
// positions spread from 0.2565 to 0.30 (q = 64: powers from 2^-125.6 to 2^-111; the flush is at
// 0.2555, the cutoff at 0.25). A light of 2^110 makes them visible, and each must be what the
// reference says, not 0: a cutoff any higher would drop whole vectors of them.
TEST(Specular, HighlightsJustAboveTheFlushAreShaded) {
  PHONGCL_REQUIRE_DEVICE(shader);
  Scene scene;
  scene.camera.eye = {0.0, 0.0, 0.0};
  scene.ambient = glm::dvec3(0.0);
  scene.lights.push_back({LightType::directional, {}, {0.0, 0.0, -1.0}, glm::dvec3(std::ldexp(1.0, 110))});
  scene.materials.push_back({"needle", glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(1.0), 64.0});
  GBuffer gbuffer;
  gbuffer.width = 64;
  gbuffer.height = 1;
  gbuffer.data_window = gbuffer.display_window = PixelWindow{0, 0, gbuffer.width - 1, 0};
  for (auto* planes : {&gbuffer.position, &gbuffer.normal})
    for (Plane& plane : *planes) plane.assign(gbuffer.pixel_count(), 0.0f);
  gbuffer.material.assign(gbuffer.pixel_count(), 0.0f);
  for (int i = 0; i < gbuffer.width; ++i) {
    const double cosine = 0.2565 + (0.30 - 0.2565) * i / (gbuffer.width - 1);  // v.z at P = (x, 0, -1)
    gbuffer.position[0][i] = static_cast<float>(std::sqrt(1.0 / (cosine * cosine) - 1.0));
    gbuffer.position[2][i] = -1.0f;
    gbuffer.normal[2][i] = 1.0f;
  }
  const Image want = reference_image(scene, gbuffer);
  for (Precision precision : {Precision::precise, Precision::fast, Precision::double_precision}) {
    if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
    for (int lanes : {1, 16}) {
      ShadeOptions options;
      options.precision = precision;
      options.lanes = lanes;
      const Image got = shader.shade(scene, gbuffer, options).image;
      const ErrorStats stats = shading_error(got, want);
      EXPECT_LE(stats.max_rel, kRelativeBound) << to_string(precision) << ", " << lanes << " lanes: "
                                               << describe_worst(stats);
      EXPECT_GT(got.pixel(0)[0], 0.0f) << to_string(precision) << ", " << lanes << " lanes";
    }
  }
}

TEST(Specular, TheRecipeCompilesInOnlyTheModelsUsed) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const DeviceInfo& device = shader.compute().device.info;
  {
    const auto [scene, gbuffer] = random_scene({}, 3);
    const Recipe recipe = make_recipe(scene, gbuffer, device, {});
    EXPECT_EQ(recipe.value("SPECULAR_MODELS"), "1");
    EXPECT_EQ(recipe.summary().find("model"), std::string::npos) << recipe.summary();
  }
  {
    const auto [scene, gbuffer] = scene_with_models({SpecularModel::blinn_phong_normalized}, 3, false);
    const Recipe recipe = make_recipe(scene, gbuffer, device, {});
    EXPECT_EQ(recipe.value("SPECULAR_MODELS"), "8");
    EXPECT_NE(recipe.summary().find("specular model blinn-phong-normalized"), std::string::npos) << recipe.summary();
  }
  {
    const auto [scene, gbuffer] = scene_with_models({SpecularModel::phong, SpecularModel::blinn_phong}, 3, false);
    const Recipe recipe = make_recipe(scene, gbuffer, device, {});
    EXPECT_EQ(recipe.value("SPECULAR_MODELS"), "5");
    EXPECT_NE(recipe.summary().find("specular models phong, blinn-phong"), std::string::npos) << recipe.summary();
  }
  {
    auto [scene, gbuffer] = scene_with_models({SpecularModel::blinn_phong}, 3, false);
    for (Material& m : scene.materials) m.ks = glm::dvec3(0.0);
    const Recipe recipe = make_recipe(scene, gbuffer, device, {});
    EXPECT_EQ(recipe.value("SPECULAR"), "0");
    EXPECT_EQ(recipe.value("SPECULAR_MODELS"), "1") << "no specular: no lobe compiled in";
  }
}

// --- Directional albedo: A(v) = (1/pi) * integral over the lit hemisphere of the lobe, for ks = 1,
// Li = 1, F = 1 (the lobe carries n.l where the model takes it; the 1/pi is the one phongcl folds
// into Li). A white surface reflects at most what it receives where A <= 1.

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from the Chebyshev guesses).
std::vector<std::pair<double, double>> gauss_legendre(int n) {
  std::vector<std::pair<double, double>> rule;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.push_back({x, 2.0 / ((1.0 - x * x) * derivative * derivative)});
  }
  return rule;
}

// In spherical coordinates around the mirror direction m of v, where every lobe peaks: the polar
// angle in panels that double from the lobe's width 1/sqrt(q + 1) to pi, 48-point Gauss-Legendre
// on each, and 1024 azimuths (the periodic trapezoid rule is spectrally accurate for a smooth ring).
// The normalised lobes vanish at the horizon with n.l: a kink there, not a jump (the classic ones jump).
double directional_albedo(SpecularModel model, double view_deg, double q) {
  static const auto rule = gauss_legendre(48);
  const glm::dvec3 n(0.0, 0.0, 1.0);
  const double theta_v = view_deg * kPi / 180.0;
  const glm::dvec3 v(std::sin(theta_v), 0.0, std::cos(theta_v));
  const glm::dvec3 m = 2.0 * glm::dot(n, v) * n - v;
  const glm::dvec3 e1 = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), m)), e2 = glm::cross(m, e1);
  std::vector<double> edges = {0.0};
  for (double edge = 1.0 / std::sqrt(q + 1.0); edge < kPi; edge *= 2.0) edges.push_back(edge);
  edges.push_back(kPi / 2.0);  // the horizon, where the integrand has a kink, seen from straight above
  edges.push_back(kPi);
  std::sort(edges.begin(), edges.end());
  constexpr int kAzimuths = 1024;
  double sum = 0.0;
  for (std::size_t panel = 0; panel + 1 < edges.size(); ++panel) {
    const double half = (edges[panel + 1] - edges[panel]) / 2.0, middle = (edges[panel + 1] + edges[panel]) / 2.0;
    for (const auto& [x, weight] : rule) {
      const double alpha = middle + half * x;
      double ring = 0.0;
      for (int k = 0; k < kAzimuths; ++k) {
        const double phi = 2.0 * kPi * k / kAzimuths;
        const glm::dvec3 l = std::cos(alpha) * m + std::sin(alpha) * (std::cos(phi) * e1 + std::sin(phi) * e2);
        if (glm::dot(n, l) > 0.0) ring += reference_specular_lobe(model, n, v, l, q);
      }
      sum += weight * half * std::sin(alpha) * ring * (2.0 * kPi / kAzimuths);
    }
  }
  return sum / kPi;
}

// Blinn-Phong normalised by (q+8)/8 at normal incidence, in closed form: with v = n, n.h = cos(t/2)
// for l at angle t, and the integral of cos^q(t/2) cos t sin t over the hemisphere is
// 8 pi (q + 2^(-q/2)) / ((q+2)(q+4)) (Giesen 2009), so A = (q+8)(q + 2^(-q/2)) / ((q+2)(q+4)):
// 1 at q = 0, above 1 for q > 0 (the approximation is slightly too large), most at q = 8.76:
// 1.0752, and 1 + 2/q for large q.
double blinn_normal_incidence(double q) { return (q + 8.0) * (q + std::pow(2.0, -q / 2.0)) / ((q + 2.0) * (q + 4.0)); }
constexpr double kBlinnOvershoot = 1.0752012;  // its maximum over q

// The quadrature's error, measured against the closed forms (normal incidence at every q; q = 0
// from every view): below 5e-6. The bound is 1e-5.
constexpr double kQuadrature = 1e-5;

TEST(Specular, NormalisedLobesReflectAtMostWhatTheyReceive) {
  for (double q : {0.0, 1.0, 10.0, 100.0, 1e3, 1e4}) {
    // Normal incidence in closed form: Phong's lobe (q+2)/2 cos^q(t) cos(t) integrates to exactly 1.
    EXPECT_NEAR(directional_albedo(SpecularModel::phong_normalized, 0.0, q), 1.0, kQuadrature) << "q = " << q;
    EXPECT_NEAR(directional_albedo(SpecularModel::blinn_phong_normalized, 0.0, q), blinn_normal_incidence(q), kQuadrature)
        << "q = " << q;
    for (double view_deg : {0.0, 30.0, 60.0, 80.0, 89.0}) {
      const double phong = directional_albedo(SpecularModel::phong_normalized, view_deg, q);
      const double blinn = directional_albedo(SpecularModel::blinn_phong_normalized, view_deg, q);
      // At q = 0 both lobes are n.l itself: A = 1 exactly, from every view.
      if (q == 0.0) {
        EXPECT_NEAR(phong, 1.0, kQuadrature) << "view " << view_deg;
        EXPECT_NEAR(blinn, 1.0, kQuadrature) << "view " << view_deg;
      }
      EXPECT_LE(phong, 1.0 + kQuadrature) << "phong-normalized, q = " << q << ", view " << view_deg;
      // Blinn's (q+8)/8 overshoots by at most its normal-incidence value at this q.
      EXPECT_LE(blinn, blinn_normal_incidence(q) + kQuadrature) << "blinn-phong-normalized, q = " << q << ", view " << view_deg;
      EXPECT_LE(blinn, kBlinnOvershoot + kQuadrature) << "q = " << q << ", view " << view_deg;
    }
  }
}

// The classic lobes are not normalised, and the test sees it: at q = 0 both are 1 over the whole
// lit hemisphere without the cosine, A = 2.
TEST(Specular, ClassicLobesAreNotNormalised) {
  // (The lobe jumps at the horizon, which the panels do not follow: a looser 2%.)
  for (double view_deg : {0.0, 60.0})
    for (SpecularModel model : {SpecularModel::phong, SpecularModel::blinn_phong})
      EXPECT_NEAR(directional_albedo(model, view_deg, 0.0), 2.0, 0.04) << to_string(model) << ", view " << view_deg;
}

}  // namespace
}  // namespace phongcl
