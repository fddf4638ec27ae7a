// Area lights: the reference's quadrature against closed forms and against itself at twice the
// order, and the kernel (Lambert's formula, the disk's closed form, the specular lobes in every model) against
// the reference on points that see the emitters whole, cut by their horizon, and from behind.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <random>
#include <vector>

#include "reference/reference_area.h"
#include "area_test_scenes.h"
#include "scene/area_light_json.h"
#include "shading_support.h"

namespace phongcl {
namespace {

using testing::area_scene;
using testing::AreaScene;
using testing::disk_light;
using testing::emitters;
using testing::rect_light;
using testing::term_error;
using testing::TermError;

constexpr double kPi = 3.14159265358979323846;

// The irradiance of a point on the axis of a parallel rect it faces: four corner form factors
// (Siegel and Howell), F = 1/(2 pi) sum [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + (A <-> B)], E = pi F.
double rect_on_axis(double width, double height, double h) {
  const double a = width / 2.0 / h, b = height / 2.0 / h;
  const double corner = a / std::sqrt(1 + a * a) * std::atan(b / std::sqrt(1 + a * a)) +
                        b / std::sqrt(1 + b * b) * std::atan(a / std::sqrt(1 + b * b));
  return 4.0 * corner / 2.0;
}

TEST(AreaReference, MatchesClosedFormsOnTheAxis) {
  const glm::dvec3 down(0, 0, -1), n(0, 0, 1);
  for (double h : {1e-3, 0.1, 1.0, 30.0}) {
    const AreaLight disk = disk_light({0, 0, h}, down, 1.0);
    const double exact_disk = kPi * 0.25 / (h * h + 0.25);  // pi sin^2 of the half angle
    const AreaIntegrals d = reference_area_integrals(disk, {0, 0, 0}, n, n, SpecularModel::phong, 0.0);
    EXPECT_NEAR(d.irradiance, exact_disk, 1e-12 * exact_disk) << "disk at h = " << h;
    const AreaLight rect = rect_light({0, 0, h}, down, {0, 1, 0}, {2.0, 0.5});
    const double exact_rect = rect_on_axis(2.0, 0.5, h);
    const AreaIntegrals r = reference_area_integrals(rect, {0, 0, 0}, n, n, SpecularModel::phong, 0.0);
    EXPECT_NEAR(r.irradiance, exact_rect, 1e-12 * exact_rect) << "rect at h = " << h;
    // q = 0: S is the solid angle; the disk's is 2 pi (1 - cos of the half angle).
    EXPECT_NEAR(d.highlight, 2 * kPi * (1 - h / std::sqrt(h * h + 0.25)), 1e-11) << "disk solid angle at h = " << h;
  }
}

// Converged: doubling the order changes nothing that matters, cut by the horizon or not, for every
// specular model up to the highest q the kernel is held to against it.
TEST(AreaReference, ConvergesAtTheDefaultOrder) {
  std::mt19937 rng(2207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 100; ++k) {
    const glm::dvec3 p(unit(rng) * 2, unit(rng) * 2, -1.0 + unit(rng));
    const glm::dvec3 n = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng) + 0.5));
    glm::dvec3 eye = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng) + 0.5));
    if (glm::dot(eye, n) < 0.0) eye = -eye;  // the pixel faces the eye, as a G-buffer's do (Blinn's kink: reference_area.h)
    const AreaLight light = k % 2 ? rect_light({0, 0, 1}, {0.2, 0.1, -1}, {0, 1, 0}, {1.5, 0.7})
                                  : disk_light({0, 0, 1}, {0.2, 0.1, -1}, 1.2);
    for (SpecularModel model : kSpecularModels)
      for (double q : {0.0, 1.0, 37.5, 100.0}) {
        const AreaIntegrals base = reference_area_integrals(light, p, n, eye, model, q, 48);
        const AreaIntegrals fine = reference_area_integrals(light, p, n, eye, model, q, 96);
        worst = std::max(worst, std::abs(base.irradiance - fine.irradiance) / std::max(fine.irradiance, 1e-3));
        worst = std::max(worst, std::abs(base.highlight - fine.highlight) / std::max(fine.highlight, 1e-3));
      }
  }
  std::cout << "reference, order 48 against 96: largest relative difference " << worst << "\n";
  EXPECT_LE(worst, 1e-6);
}

TEST(AreaLights, DiffuseMatchesTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (bool rect : {true, false}) {
    for (Precision precision : {Precision::precise, Precision::double_precision}) {
      if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
      const AreaScene s = area_scene(emitters(rect), glm::dvec3(0.0), 1.0, rect ? 501 : 502);
      ShadeOptions options;
      options.precision = precision;
      const ShadeResult result = shader.shade(s.scene, s.gbuffer, options);
      EXPECT_NE(result.build_options.find("-DAREA_LIGHTS=1"), std::string::npos);
      const TermError error = term_error(result.image, reference_image(s.scene, s.gbuffer));
      std::cout << (rect ? "rects" : "disks") << ", " << to_string(precision) << ": diffuse against the reference, "
                << error.lit << " lit pixels, median " << error.median_rel << ", max " << error.max_rel << " (pixel "
                << error.worst << ": " << error.worst_kernel << " against " << error.worst_reference << ")\n";
      EXPECT_GT(error.lit, s.gbuffer.pixel_count() / 2);
      // Rects: Lambert's sum of O(1) edge terms, each to a few ulp, cancelling to a faint E where the
      // emitter is a sliver over the horizon (2.2e-5 measured in float); in double what remains is
      // the light's geometry rounded to float (4.4e-6). The disk cut by the horizon is the clipped
      // sum of the area-matched 64-gon, not exact: 7.3e-5 measured in both precisions.
      const double bound = rect ? (precision == Precision::precise ? 5e-5 : 1e-5) : 2e-4;
      EXPECT_LE(error.max_rel, bound) << (rect ? "rects" : "disks") << ", " << to_string(precision);
    }
  }
}

// A light group's layer is the reference's image of that group's lights alone, area and point
// lights together (ks 0: the area lights' S is a stated quadrature, measured apart below).
TEST(AreaLights, GroupLayersMatchTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  std::vector<AreaLight> lights = emitters(true);
  lights[0].group = "top";
  lights[1].group = "wall";
  AreaScene s = area_scene(lights, glm::dvec3(0.0), 1.0, 503);
  Light point;
  point.position = {0.5, 2.0, 0.5};
  point.color = glm::dvec3(0.3);
  point.group = "top";
  s.scene.lights.push_back(point);
  ShadeOptions options;
  options.write_terms = true;
  const ShadeResult result = shader.shade(s.scene, s.gbuffer, options);
  const std::vector<std::string> names{"top", "wall"};
  ASSERT_EQ(result.terms.group_names, names);
  EXPECT_EQ(result.recipe.value("LIGHT_GROUPS"), "2");
  for (std::size_t g = 0; g < names.size(); ++g) {
    const TermError error =
        term_error(result.terms.groups[g], reference_image(reference_group_scene(s.scene, names[g]), s.gbuffer));
    std::cout << "group " << names[g] << ": against the reference, " << error.lit << " lit pixels, median "
              << error.median_rel << ", max " << error.max_rel << "\n";
    EXPECT_GT(error.lit, s.gbuffer.pixel_count() / 10) << names[g];
    EXPECT_LE(error.max_rel, 5e-5) << names[g];  // the rects' bound of DiffuseMatchesTheReference
  }
}

// An area light's group and shadows compile in only where asked: without them its scene builds the
// options it built before either existed.
TEST(AreaLights, GroupsAndShadowsCompileInOnlyWhenAsked) {
  PHONGCL_REQUIRE_DEVICE(shader);
  AreaScene s = area_scene(emitters(false), glm::dvec3(0.0), 1.0, 504);
  const DeviceInfo& device = shader.compute().device.info;
  ShadeOptions terms;
  terms.write_terms = true;
  auto value = [&](const char* flag, const ShadeOptions& options) {
    return make_recipe(s.scene, s.gbuffer, device, options).value(flag);
  };
  EXPECT_EQ(value("LIGHT_GROUPS", terms), "0");
  EXPECT_EQ(value("SHADOWS", terms), "0");
  s.scene.area_lights[1].group = "wall";
  EXPECT_EQ(value("LIGHT_GROUPS", terms), "1") << "an area light's group is a group";
  EXPECT_EQ(value("LIGHT_GROUPS", {}), "0") << "groups are layers of the terms";
  s.scene.area_lights[0].shadows = true;
  EXPECT_EQ(value("SHADOWS", {}), "1");
  EXPECT_EQ(value("SCREEN_SHADOWS", {}), "1") << "no objects: the march";
  ShadeOptions off;
  off.shadows.mode = ShadowMode::off;
  EXPECT_EQ(value("SHADOWS", off), "0");
}

// A range ends an area light exactly: beyond it the light adds no bit, and a work-item whose every
// pixel is beyond it skips the light (a skip too eager shows against the reference). Pixels are
// laid out along x so that lane vectors share an x and most of them are wholly in or out of range.
TEST(AreaLights, NothingBeyondTheRange) {
  PHONGCL_REQUIRE_DEVICE(shader);
  std::vector<AreaLight> lights = emitters(true);
  lights[1].position = {-2.0, 0.8, 0.0};
  lights[1].range = 1.5;
  AreaScene s = area_scene(lights, glm::dvec3(0.0), 1.0, 505);  // ks 0: the reference's E is exact
  const std::size_t pixels = s.gbuffer.pixel_count();
  std::vector<std::size_t> order(pixels);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.gbuffer.position[0][a] < s.gbuffer.position[0][b]; });
  GBuffer sorted = s.gbuffer;
  for (std::size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) {
      sorted.position[c][i] = s.gbuffer.position[c][order[i]];
      sorted.normal[c][i] = s.gbuffer.normal[c][order[i]];
    }
  const Image lit = shader.shade(s.scene, sorted, {}).image;
  Scene without = s.scene;
  without.area_lights.pop_back();
  const Image unlit = shader.shade(without, sorted, {}).image;
  std::size_t beyond = 0, reached = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const glm::dvec3 p(sorted.position[0][i], sorted.position[1][i], sorted.position[2][i]);
    const double distance = glm::length(p - lights[1].position);
    if (distance >= lights[1].range) {
      ++beyond;
      for (int c = 0; c < 4; ++c) ASSERT_EQ(lit.pixel(i)[c], unlit.pixel(i)[c]) << "pixel " << i << " at " << distance;
    } else if (lit.pixel(i)[0] != unlit.pixel(i)[0]) {
      ++reached;
    }
  }
  EXPECT_GT(beyond, pixels / 2);
  EXPECT_GT(reached, pixels / 20) << "the light reached almost nothing within its range";
  const TermError error = term_error(lit, reference_image(s.scene, sorted));
  EXPECT_LE(error.max_rel, 5e-5) << "pixel " << error.worst;  // the rects' bound of DiffuseMatchesTheReference
}

// A rect and a disk at the readers' size bound (kMaxAreaLightSize), close by, shade to finite
// pixels; past it they are refused before they reach the kernel (a rect of 1e20 x 1e20 shaded to NaN).
TEST(AreaLights, LightsAtTheSizeBoundShadeFinite) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (bool rect : {true, false}) {
    std::vector<AreaLight> lights = emitters(rect);
    lights[0].size = glm::dvec2(kMaxAreaLightSize);
    const AreaScene s = area_scene(lights, glm::dvec3(1.0), 10.0, 506);
    EXPECT_NO_THROW(check_area_lights(s.scene.area_lights));
    for (Precision precision : {Precision::precise, Precision::double_precision}) {
      if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
      SCOPED_TRACE(std::string(rect ? "rect, " : "disk, ") + to_string(precision));
      ShadeOptions options;
      options.precision = precision;
      const Image image = shader.shade(s.scene, s.gbuffer, options).image;
      std::size_t lit = 0;
      for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(image.pixel(i)[c])) << "pixel " << i;
        lit += image.pixel(i)[0] > 0.0f;
      }
      EXPECT_GT(lit, image.pixel_count() / 2);
    }
    lights[0].size = glm::dvec2(100 * kMaxAreaLightSize);
    EXPECT_THROW(check_area_lights(lights), std::invalid_argument) << (rect ? "rect" : "disk");
  }
}

// S in every specular model against the reference, on the pixels of area_scene. Phong's lobes are
// in closed form at integer q (phong_polygon.h), so the bound is the float rounding of the
// recurrences and of the light's geometry, as E's; at q = 0.5, 2.5 and 7.5 the edge rule's Gauss
// points add about 1e-7 (docs/shading.md), and at q = 37.5 the log-linear interpolation between
// q = 37 and 38 at most 1/(8 q^2) = 9e-5. A disk's S is its inscribed 64-gon's in closed form
// plus its rim's by a rule. Blinn's lobes are the 4x4 rule's: only printed, their error is what it
// measures (docs/shading.md).
TEST(AreaLights, SpecularMatchesTheReference) {
  PHONGCL_REQUIRE_DEVICE(shader);
  for (bool rect : {true, false})
    for (SpecularModel model : kSpecularModels)
      for (double q : {0.0, 0.5, 1.0, 2.5, 7.5, 10.0, 37.5, 100.0}) {
        AreaScene s = area_scene(emitters(rect), glm::dvec3(1.0), q, 600);
        s.scene.materials[0].kd = glm::dvec3(0.0);
        s.scene.materials[0].specular_model = model;
        const Image reference = reference_image(s.scene, s.gbuffer);
        for (Precision precision : {Precision::precise, Precision::double_precision}) {
          if (precision == Precision::double_precision && !shader.compute().device.info.has_fp64) continue;
          ShadeOptions options;
          options.precision = precision;
          const TermError error = term_error(shader.shade(s.scene, s.gbuffer, options).image, reference);
          const bool closed_form = model == SpecularModel::phong || model == SpecularModel::phong_normalized;
          std::cout << (rect ? "rects" : "disks") << ", " << to_string(model) << ", q = " << q << ", "
                    << to_string(precision) << ": S against the reference, " << error.lit << " lit pixels, median "
                    << error.median_rel << ", max " << error.max_rel << " (pixel " << error.worst << ": "
                    << error.worst_kernel << " for " << error.worst_reference << ")\n";
          EXPECT_GT(error.lit, 0u);
          if (closed_form) {
            EXPECT_LE(error.max_rel, 1e-3) << to_string(model) << " q = " << q;
          }
        }
      }
}

}  // namespace
}  // namespace phongcl
