// The scalar reference against values worked out by hand from the formula (docs/shading.md "The
// formula"). Each case states its geometry and derivation; expected values never come from the
// code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/error.h"
#include "reference/reference.h"

namespace phongcl {
namespace {

const double kSqrt3 = std::sqrt(3.0);

// Per-channel comparison with an absolute tolerance; `what` names the case and the term.
void expect_near3(const glm::dvec3& got, const glm::dvec3& want, double tolerance, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance) << what << ", channel " << c;
}

// Relative comparison for HDR magnitudes.
void expect_rel3(const glm::dvec3& got, const glm::dvec3& want, double tolerance, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_LE(std::abs(got[c] - want[c]), tolerance * std::abs(want[c]))
        << what << ", channel " << c << ": got " << got[c] << " want " << want[c];
}

Light point_light(glm::dvec3 position, glm::dvec3 color) {
  Light light;
  light.type = LightType::point;
  light.position = position;
  light.color = color;
  return light;
}

Light directional_light(glm::dvec3 direction, glm::dvec3 color) {
  Light light;
  light.type = LightType::directional;
  light.direction = direction;
  light.color = color;
  return light;
}

// A surface at the origin facing +z, with distinct channels so a swapped channel shows.
SurfacePoint surface(double shininess) {
  SurfacePoint p;
  p.position = {0.0, 0.0, 0.0};
  p.normal = {0.0, 0.0, 1.0};
  p.ka = {0.1, 0.2, 0.3};
  p.kd = {0.5, 0.25, 0.125};
  p.ks = {0.25, 0.5, 0.75};
  p.shininess = shininess;
  return p;
}

Scene scene_with(glm::dvec3 eye, std::vector<Light> lights, glm::dvec3 ambient = {0.0, 0.0, 0.0}) {
  Scene scene;
  scene.camera.eye = eye;
  scene.ambient = ambient;
  scene.lights = std::move(lights);
  return scene;
}

const glm::dvec3 kLi{2.0, 3.0, 4.0};
const glm::dvec3 kZero{0.0};

TEST(ReferenceShade, AmbientOnly) {
  // No lights: L_o = ka * La = (0.1*0.5, 0.2*1, 0.3*2).
  const Scene scene = scene_with({0, 0, 5}, {}, {0.5, 1.0, 2.0});
  const ShadingTerms t = reference_shade_point(scene, surface(10.0));
  expect_near3(t.ambient, {0.05, 0.2, 0.6}, 1e-15, "ambient only: ambient");
  expect_near3(t.diffuse, kZero, 0.0, "ambient only: diffuse");
  expect_near3(t.specular, kZero, 0.0, "ambient only: specular");
  expect_near3(t.total(), {0.05, 0.2, 0.6}, 1e-15, "ambient only: total");
}

TEST(ReferenceShade, HeadOnPointLight) {
  // n = (0,0,1), light at (0,0,5) from P = 0: l = n, ndl = 1 -> diffuse = kd*Li = (1, 0.75, 0.5).
  // r = 2*1*n - l = n; eye at (0,0,5): v = n, v.r = 1 -> specular = ks*Li = (0.5, 1.5, 3).
  const Scene scene = scene_with({0, 0, 5}, {point_light({0, 0, 5}, kLi)}, {1, 1, 1});
  const ShadingTerms t = reference_shade_point(scene, surface(10.0));
  expect_near3(t.ambient, {0.1, 0.2, 0.3}, 1e-15, "head-on: ambient");
  expect_near3(t.diffuse, {1.0, 0.75, 0.5}, 1e-12, "head-on: diffuse");
  expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, "head-on: specular");
  expect_near3(t.total(), {1.6, 2.45, 3.8}, 1e-12, "head-on: total");
}

TEST(ReferenceShade, SixtyDegreeIncidence) {
  // Light at 4*(sin60, 0, cos60) = (2*sqrt3, 0, 2): l = (sqrt3/2, 0, 1/2), ndl = 0.5
  // -> diffuse = 0.5*kd*Li = (0.5, 0.375, 0.25). r = 2*0.5*n - l = (-sqrt3/2, 0, 1/2).
  const SurfacePoint p = surface(8.0);
  const Light light = point_light({2 * kSqrt3, 0, 2}, kLi);

  // Eye on the mirror direction (-2*sqrt3, 0, 2): v = r, v.r = 1 -> specular = ks*Li.
  ShadingTerms t = reference_shade_point(scene_with({-2 * kSqrt3, 0, 2}, {light}), p);
  expect_near3(t.diffuse, {0.5, 0.375, 0.25}, 1e-12, "ndl=0.5 case: diffuse");
  expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, "ndl=0.5, eye on mirror direction: specular");

  // Eye straight above at (0,0,5): v = (0,0,1), v.r = 1/2 -> specular = ks*Li*(1/2)^8 = ks*Li/256.
  t = reference_shade_point(scene_with({0, 0, 5}, {light}), p);
  expect_near3(t.diffuse, {0.5, 0.375, 0.25}, 1e-12, "ndl=0.5, eye above: diffuse");
  expect_near3(t.specular, glm::dvec3{0.5, 1.5, 3.0} / 256.0, 1e-12, "ndl=0.5, eye above, q=8: specular");
}

TEST(ReferenceShade, BackFacingAndGrazingLightGiveNothing) {
  // Light below the surface (0,0,-5): ndl = -1 <= 0 -> no diffuse, no specular, even with q = 0
  // (which would otherwise give pow(0,0) = 1).
  for (double q : {0.0, 8.0}) {
    const ShadingTerms t =
        reference_shade_point(scene_with({0, 0, -5}, {point_light({0, 0, -5}, kLi)}), surface(q));
    expect_near3(t.diffuse, kZero, 0.0, "back-facing light, q=" + std::to_string(q) + ": diffuse");
    expect_near3(t.specular, kZero, 0.0, "back-facing light, q=" + std::to_string(q) + ": specular");
  }
  // Light in the tangent plane (5,0,0): ndl = 0, not > 0 -> nothing.
  const ShadingTerms t =
      reference_shade_point(scene_with({0, 0, 5}, {point_light({5, 0, 0}, kLi)}), surface(0.0));
  expect_near3(t.diffuse, kZero, 0.0, "grazing light ndl=0: diffuse");
  expect_near3(t.specular, kZero, 0.0, "grazing light ndl=0, q=0: specular");
}

TEST(ReferenceShade, DirectionalLightTravelsAlongDirection) {
  // direction = (0,0,-7) travels down onto the +z-facing surface: l = -normalize(direction) = (0,0,1),
  // ndl = 1 -> diffuse = kd*Li, and with the eye above, specular = ks*Li.
  ShadingTerms t =
      reference_shade_point(scene_with({0, 0, 5}, {directional_light({0, 0, -7}, kLi)}), surface(8.0));
  expect_near3(t.diffuse, {1.0, 0.75, 0.5}, 1e-12, "directional (0,0,-7): diffuse");
  expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, "directional (0,0,-7): specular");

  // direction = (0,0,+1) travels away from the surface: l = (0,0,-1), ndl = -1 -> nothing.
  t = reference_shade_point(scene_with({0, 0, 5}, {directional_light({0, 0, 1}, kLi)}), surface(8.0));
  expect_near3(t.diffuse, kZero, 0.0, "directional (0,0,1) from below: diffuse");
  expect_near3(t.specular, kZero, 0.0, "directional (0,0,1) from below: specular");

  // direction = -3*(sqrt3/2, 0, 1/2): l = (sqrt3/2, 0, 1/2), ndl = 0.5 -> diffuse = 0.5*kd*Li.
  t = reference_shade_point(scene_with({0, 0, 5}, {directional_light({-1.5 * kSqrt3, 0, -1.5}, kLi)}),
                            surface(8.0));
  expect_near3(t.diffuse, {0.5, 0.375, 0.25}, 1e-12, "directional at 60 degrees: diffuse");
}

TEST(ReferenceShade, SpecularExponent) {
  // Light head-on: r = n = (0,0,1). Eye at 5*(sin30, 0, cos30) = (2.5, 0, 2.5*sqrt3):
  // v.r = cos30 = sqrt3/2; q = 8 -> (sqrt3/2)^8 = (3/4)^4 = 81/256 -> specular = ks*Li*81/256.
  const Scene scene = scene_with({2.5, 0, 2.5 * kSqrt3}, {point_light({0, 0, 5}, kLi)});
  ShadingTerms t = reference_shade_point(scene, surface(8.0));
  expect_near3(t.specular, glm::dvec3{0.5, 1.5, 3.0} * (81.0 / 256.0), 1e-12, "v.r=cos30, q=8: specular");
  expect_near3(t.diffuse, {1.0, 0.75, 0.5}, 1e-12, "v.r=cos30, q=8: diffuse (independent of v)");

  // q = 1 -> ks*Li*sqrt3/2; q = 0 -> ks*Li (any v.r >= 0 to the power 0 is 1).
  t = reference_shade_point(scene, surface(1.0));
  expect_near3(t.specular, glm::dvec3{0.5, 1.5, 3.0} * (kSqrt3 / 2), 1e-12, "v.r=cos30, q=1: specular");
  t = reference_shade_point(scene, surface(0.0));
  expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, "v.r=cos30, q=0: specular");
}

TEST(ReferenceShade, ZeroExponentWithNegativeViewDotReflection) {
  // Light at 60 degrees (2*sqrt3, 0, 2): r = (-sqrt3/2, 0, 1/2). Eye at (5,0,0): v = (1,0,0),
  // v.r = -sqrt3/2 < 0 -> base max(0, v.r) = 0. q = 0: pow(0,0) = 1 -> specular = ks*Li;
  // q = 8: pow(0,8) = 0 -> no specular. Diffuse = 0.5*kd*Li either way.
  const Scene scene = scene_with({5, 0, 0}, {point_light({2 * kSqrt3, 0, 2}, kLi)});
  ShadingTerms t = reference_shade_point(scene, surface(0.0));
  expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, "q=0, v.r<0: pow(0,0)=1");
  expect_near3(t.diffuse, {0.5, 0.375, 0.25}, 1e-12, "q=0, v.r<0: diffuse");
  t = reference_shade_point(scene, surface(8.0));
  expect_near3(t.specular, kZero, 0.0, "q=8, v.r<0: pow(0,8)=0");
}

TEST(ReferenceShade, ZeroNormalIsAmbientOnly) {
  // normalize(0) = 0 -> ndl = 0 for every light -> L_o = ka*La, even with q = 0.
  for (double q : {0.0, 8.0}) {
    SurfacePoint p = surface(q);
    p.normal = {0.0, 0.0, 0.0};
    const Scene scene =
        scene_with({0, 0, 5}, {point_light({0, 0, 5}, kLi), directional_light({0, 0, -1}, kLi)}, {1, 1, 1});
    const ShadingTerms t = reference_shade_point(scene, p);
    const std::string what = "zero normal, q=" + std::to_string(q);
    expect_near3(t.total(), {0.1, 0.2, 0.3}, 1e-15, what + ": total");
    EXPECT_TRUE(std::isfinite(t.total().x)) << what << ": no NaN from normalizing zero";
  }
}

TEST(ReferenceShade, LightAtThePointContributesNothing) {
  // Lpos == P -> l = normalize(0) = 0 -> ndl = 0 -> nothing, q = 0 included.
  for (double q : {0.0, 8.0}) {
    SurfacePoint p = surface(q);
    p.position = {1.0, -2.0, 3.0};
    const ShadingTerms t = reference_shade_point(scene_with({1, -2, 8}, {point_light({1, -2, 3}, kLi)}), p);
    const std::string what = "light at the point, q=" + std::to_string(q);
    expect_near3(t.diffuse, kZero, 0.0, what + ": diffuse");
    expect_near3(t.specular, kZero, 0.0, what + ": specular");
  }
}

TEST(ReferenceShade, EyeAtThePoint) {
  // E == P -> v = 0 -> v.r = 0 -> specular factor pow(0, q). Light head-on: diffuse = kd*Li.
  const Scene scene = scene_with({0, 0, 0}, {point_light({0, 0, 5}, kLi)});
  ShadingTerms t = reference_shade_point(scene, surface(5.0));
  expect_near3(t.diffuse, {1.0, 0.75, 0.5}, 1e-12, "eye at the point, q=5: diffuse");
  expect_near3(t.specular, kZero, 0.0, "eye at the point, q=5: pow(0,5)=0");
  t = reference_shade_point(scene, surface(0.0));
  expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, "eye at the point, q=0: pow(0,0)=1");
}

// Normal direction (2,3,6)/7 (|(2,3,6)| = 7). Light at (0,0,5): l = (0,0,1), ndl = 6/7.
// r = 2*(6/7)*n - l = (24/49, 36/49, 72/49 - 1) = (24, 36, 23)/49 (unit: 24^2+36^2+23^2 = 49^2).
// Eye at (0,0,5): v.r = 23/49; q = 3 -> specular = ks*Li*(23/49)^3; diffuse = kd*Li*6/7.
void expect_tilted_normal_shading(glm::dvec3 normal, const std::string& what) {
  SurfacePoint p = surface(3.0);
  p.normal = normal;
  const ShadingTerms t = reference_shade_point(scene_with({0, 0, 5}, {point_light({0, 0, 5}, kLi)}), p);
  expect_near3(t.diffuse, glm::dvec3{1.0, 0.75, 0.5} * (6.0 / 7.0), 1e-12, what + ": diffuse");
  expect_near3(t.specular, glm::dvec3{0.5, 1.5, 3.0} * std::pow(23.0 / 49.0, 3.0), 1e-12,
               what + ": specular");
}

TEST(ReferenceShade, NormalLengthDoesNotMatter) {
  expect_tilted_normal_shading({2.0 / 7, 3.0 / 7, 6.0 / 7}, "unit normal (2,3,6)/7");
  expect_tilted_normal_shading({2.0, 3.0, 6.0}, "normal (2,3,6)");
  expect_tilted_normal_shading(glm::dvec3{2, 3, 6} * (1e-3 / 7), "normal of length 1e-3");
  expect_tilted_normal_shading(glm::dvec3{2, 3, 6} * (1e3 / 7), "normal of length 1e3");
}

TEST(ReferenceShade, HugeAndDenormalNormals) {
  // Powers of two scale (2,3,6) exactly, so the stored normal has exactly the unit normal's direction.
  // As G-buffer floats: 2^100 ~ 1.3e30 and 2^-133 ~ 9e-41 (a float denormal), converted to double.
  expect_tilted_normal_shading(glm::dvec3(glm::vec3(2, 3, 6) * std::ldexp(1.0f, 100)),
                               "float normal *2^100 (~1e30)");
  expect_tilted_normal_shading(glm::dvec3(glm::vec3(2, 3, 6) * std::ldexp(1.0f, -133)),
                               "float normal *2^-133 (~1e-40)");
  // The literal values 1e30 and 1e-40 as floats, along the axis (any positive scale of (0,0,1) is
  // exact): head-on light, eye above -> kd*Li + ks*Li.
  for (float scale : {1e30f, 1e-40f}) {
    SurfacePoint p = surface(3.0);
    p.normal = {0.0, 0.0, static_cast<double>(scale)};
    const ShadingTerms t = reference_shade_point(scene_with({0, 0, 5}, {point_light({0, 0, 5}, kLi)}), p);
    expect_near3(t.total(), glm::dvec3{1.5, 2.25, 3.5}, 1e-12,
                 std::string("float normal (0,0,") + (scale > 1 ? "1e30)" : "1e-40)"));
  }
  // Beyond float: double squares overflow (2^1000) or underflow (2^-1040, a double denormal) here,
  // so a naive normalize would give 0 or NaN.
  expect_tilted_normal_shading(glm::dvec3{2, 3, 6} * std::ldexp(1.0, 1000), "double normal *2^1000 (~1e301)");
  expect_tilted_normal_shading(glm::dvec3{2, 3, 6} * std::ldexp(1.0, -1040),
                               "double normal *2^-1040 (~1e-313)");
}

TEST(ReferenceShade, HugeAndTinyLightAndEyeOffsets) {
  // The light and eye directions are normalized by the same rule: a light 1e300 away head-on is
  // still l = (0,0,1), and one 1e-310 above the point too.
  for (double distance : {1e300, 1e-310}) {
    const ShadingTerms t = reference_shade_point(
        scene_with({0, 0, distance}, {point_light({0, 0, distance}, kLi)}), surface(8.0));
    const std::string what = std::string("light and eye at distance ") + (distance > 1 ? "1e300" : "1e-310");
    expect_near3(t.diffuse, {1.0, 0.75, 0.5}, 1e-12, what + ": diffuse");
    expect_near3(t.specular, {0.5, 1.5, 3.0}, 1e-12, what + ": specular");
  }
}

TEST(ReferenceShade, HdrLightScalesLinearly) {
  // Li = 1e30*(2,3,4), head-on with the eye above: diffuse = kd*Li, specular = ks*Li, both
  // 1e30 times the unit-scale case (1, 0.75, 0.5) and (0.5, 1.5, 3).
  const glm::dvec3 hdr = kLi * 1e30;
  const ShadingTerms t =
      reference_shade_point(scene_with({0, 0, 5}, {point_light({0, 0, 5}, hdr)}), surface(8.0));
  expect_rel3(t.diffuse, glm::dvec3{1.0, 0.75, 0.5} * 1e30, 1e-14, "Li=1e30: diffuse");
  expect_rel3(t.specular, glm::dvec3{0.5, 1.5, 3.0} * 1e30, 1e-14, "Li=1e30: specular");
}

TEST(ReferenceShade, MultipleLightsSum) {
  // Head-on point light A = (2,3,4) and 60-degree directional light B = (1,1,1), eye above, q = 8.
  // A: ndl = 1, v.r = 1 -> diffuse kd*A = (1, 0.75, 0.5), specular ks*A = (0.5, 1.5, 3).
  // B: ndl = 0.5, v.r = 1/2 -> diffuse 0.5*kd = (0.25, 0.125, 0.0625), specular ks/256.
  const Scene scene = scene_with(
      {0, 0, 5}, {point_light({0, 0, 5}, kLi), directional_light({-kSqrt3, 0, -1}, {1, 1, 1})}, {1, 1, 1});
  const ShadingTerms t = reference_shade_point(scene, surface(8.0));
  const glm::dvec3 diffuse{1.25, 0.875, 0.5625};
  const glm::dvec3 specular = glm::dvec3{0.5, 1.5, 3.0} + glm::dvec3{0.25, 0.5, 0.75} / 256.0;
  expect_near3(t.diffuse, diffuse, 1e-12, "two lights: diffuse");
  expect_near3(t.specular, specular, 1e-12, "two lights: specular");
  expect_near3(t.total(), glm::dvec3{0.1, 0.2, 0.3} + diffuse + specular, 1e-12, "two lights: total");
}

// A w x 1 G-buffer filled by hand: P = (i, 0, 0), N = (0,0,1), material index per pixel.
GBuffer row_gbuffer(const std::vector<float>& materials) {
  GBuffer g;
  g.width = static_cast<int>(materials.size());
  g.height = 1;
  g.data_window = g.display_window = PixelWindow{0, 0, g.width - 1, 0};
  for (int c = 0; c < 3; ++c) {
    g.position[c].assign(materials.size(), 0.0f);
    g.normal[c].assign(materials.size(), c == 2 ? 1.0f : 0.0f);
  }
  for (std::size_t i = 0; i < materials.size(); ++i) g.position[0][i] = static_cast<float>(i);
  g.material = materials;
  return g;
}

Material material(glm::dvec3 ka, glm::dvec3 kd, glm::dvec3 ks, double q) {
  Material m;
  m.ka = ka;
  m.kd = kd;
  m.ks = ks;
  m.shininess = q;
  return m;
}

TEST(ReferenceSurface, TableMaterialAndFloatInputs) {
  Scene scene;
  scene.materials = {material({1, 1, 1}, {2, 2, 2}, {3, 3, 3}, 4),
                     material({0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}, {0.7, 0.8, 0.9}, 5)};
  GBuffer g = row_gbuffer({1.0f, 0.0f});
  g.position[1][0] = 0.1f;  // not exactly 0.1 as a float: the reference must see double(0.1f)
  g.normal[0][0] = 0.3f;
  const SurfacePoint p = reference_surface(scene, g, 0);
  // Copies, not arithmetic: these compare exactly.
  EXPECT_EQ(p.position, glm::dvec3(0.0, static_cast<double>(0.1f), 0.0)) << "pixel 0 position from floats";
  EXPECT_EQ(p.normal, glm::dvec3(static_cast<double>(0.3f), 0.0, 1.0)) << "pixel 0 normal from floats";
  EXPECT_EQ(p.kd, glm::dvec3(0.4, 0.5, 0.6)) << "pixel 0 uses table material 1";
  EXPECT_EQ(p.shininess, 5.0) << "pixel 0 uses table material 1";
  const SurfacePoint q = reference_surface(scene, g, 1);
  EXPECT_EQ(q.position, glm::dvec3(1.0, 0.0, 0.0)) << "pixel 1 position";
  EXPECT_EQ(q.ks, glm::dvec3(3.0)) << "pixel 1 uses table material 0";
}

TEST(ReferenceSurface, PerPixelGroupsOverrideTheTable) {
  Scene scene;
  scene.materials = {material({1, 1, 1}, {2, 2, 2}, {3, 3, 3}, 4)};
  GBuffer g = row_gbuffer({0.0f, 0.0f});
  for (int c = 0; c < 3; ++c) g.kd[c] = {0.25f * static_cast<float>(c + 1), 0.5f};
  g.shininess = {0.0f, 7.0f};
  const SurfacePoint p = reference_surface(scene, g, 0);
  EXPECT_EQ(p.ka, glm::dvec3(1.0)) << "Ka not per pixel: table";
  EXPECT_EQ(p.kd, glm::dvec3(0.25, 0.5, 0.75)) << "Kd per pixel overrides table";
  EXPECT_EQ(p.ks, glm::dvec3(3.0)) << "Ks not per pixel: table";
  EXPECT_EQ(p.shininess, 0.0) << "shininess per pixel overrides table";
  EXPECT_EQ(reference_surface(scene, g, 1).shininess, 7.0) << "pixel 1 per-pixel shininess";

  // Shading the overridden pixel: n = l = v = (0,0,1) with light (2,3,4) above pixel 0 at (0,0,5)
  // -> diffuse = per-pixel kd*Li = (0.5, 1.5, 3), specular = table ks*Li*1^0 = (6, 9, 12).
  scene.camera.eye = {0, 0, 5};
  scene.lights = {point_light({0, 0, 5}, kLi)};
  const ShadingTerms t = reference_shade_point(scene, p);
  expect_near3(t.diffuse, {0.5, 1.5, 3.0}, 1e-12, "per-pixel Kd: diffuse");
  expect_near3(t.specular, {6.0, 9.0, 12.0}, 1e-12, "table Ks, per-pixel q=0: specular");
}

TEST(ReferenceSurface, AllGroupsPerPixelNeedNoTable) {
  Scene scene;  // no materials at all
  GBuffer g = row_gbuffer({3.0f});
  for (int c = 0; c < 3; ++c) {
    g.ka[c] = {0.125f};
    g.kd[c] = {0.25f};
    g.ks[c] = {0.5f};
  }
  g.shininess = {2.0f};
  SurfacePoint p;
  ASSERT_NO_THROW(p = reference_surface(scene, g, 0)) << "empty table, all four groups per pixel";
  EXPECT_EQ(p.ka, glm::dvec3(0.125)) << "all per pixel: Ka";
  EXPECT_EQ(p.kd, glm::dvec3(0.25)) << "all per pixel: Kd";
  EXPECT_EQ(p.ks, glm::dvec3(0.5)) << "all per pixel: Ks";
  EXPECT_EQ(p.shininess, 2.0) << "all per pixel: shininess";
}

TEST(ReferenceSurface, IndexOutsideTheTableThrows) {
  Scene scene;
  scene.materials = {material({1, 1, 1}, {2, 2, 2}, {3, 3, 3}, 4)};
  const GBuffer g = row_gbuffer({1.0f});
  EXPECT_THROW(reference_surface(scene, g, 0), InputError) << "material 1 with a one-entry table";
}

TEST(ReferenceImage, ShadedBackgroundAndNonFinitePixels) {
  // Pixel 0: material 0 at P = 0, n = (0,0,1), light (2,3,4) and eye at (0,0,5), La = 1:
  // ka + kd*Li + ks*Li = (0.1,0.2,0.3) + (1,0.75,0.5) + (0.5,1.5,3) = (1.6, 2.45, 3.8), alpha 1.
  // Pixel 1: material -1 -> background (0.25, 0.5, 0.75), alpha 0.
  // Pixel 2: material 0 but P.x = NaN -> not shaded -> background, alpha 0.
  Scene scene = scene_with({0, 0, 5}, {point_light({0, 0, 5}, kLi)}, {1, 1, 1});
  const SurfacePoint s = surface(8.0);
  scene.materials = {material(s.ka, s.kd, s.ks, s.shininess)};
  scene.background = {0.25, 0.5, 0.75};
  GBuffer g = row_gbuffer({0.0f, -1.0f, 0.0f});
  g.position[0][2] = std::numeric_limits<float>::quiet_NaN();
  g.data_window = PixelWindow{10, 20, 12, 20};
  g.display_window = PixelWindow{0, 0, 99, 49};

  const Image image = reference_image(scene, g);
  ASSERT_EQ(image.width, 3) << "3x1 G-buffer";
  ASSERT_EQ(image.height, 1) << "3x1 G-buffer";
  ASSERT_EQ(image.rgba.size(), 12u) << "3x1 G-buffer";
  EXPECT_EQ(image.data_window.x_min, 10) << "data window carried from the G-buffer";
  EXPECT_EQ(image.data_window.y_max, 20) << "data window carried from the G-buffer";
  EXPECT_EQ(image.display_window.x_max, 99) << "display window carried from the G-buffer";

  const float shaded[4] = {1.6f, 2.45f, 3.8f, 1.0f};
  const float background[4] = {0.25f, 0.5f, 0.75f, 0.0f};
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(image.pixel(0)[c], shaded[c], 1e-6) << "shaded pixel 0, channel " << c;
    EXPECT_NEAR(image.pixel(1)[c], background[c], 1e-7) << "background pixel 1 (material -1), channel " << c;
    EXPECT_NEAR(image.pixel(2)[c], background[c], 1e-7) << "NaN position pixel 2, channel " << c;
  }
}

TEST(ReferenceImage, TermImagesAreEachTermAlone) {
  // The pixel of ShadedBackgroundAndNonFinitePixels: ka (0.1, 0.2, 0.3), kd Li (1, 0.75, 0.5), ks Li
  // (0.5, 1.5, 3); the background pixel's terms are 0 with alpha 0.
  Scene scene = scene_with({0, 0, 5}, {point_light({0, 0, 5}, kLi)}, {1, 1, 1});
  const SurfacePoint s = surface(8.0);
  scene.materials = {material(s.ka, s.kd, s.ks, s.shininess)};
  scene.background = {0.25, 0.5, 0.75};
  ReferenceTermImages terms;
  reference_image(scene, row_gbuffer({0.0f, -1.0f}), {}, {}, &terms);
  const float ambient[3] = {0.1f, 0.2f, 0.3f}, diffuse[3] = {1.0f, 0.75f, 0.5f}, specular[3] = {0.5f, 1.5f, 3.0f};
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(terms.ambient.pixel(0)[c], ambient[c], 1e-6) << "ambient, channel " << c;
    EXPECT_NEAR(terms.diffuse.pixel(0)[c], diffuse[c], 1e-6) << "diffuse, channel " << c;
    EXPECT_NEAR(terms.specular.pixel(0)[c], specular[c], 1e-6) << "specular, channel " << c;
    EXPECT_EQ(terms.specular.pixel(1)[c], 0.0f) << "background pixel, channel " << c;
  }
  EXPECT_EQ(terms.diffuse.pixel(0)[3], 1.0f) << "a shaded pixel's alpha";
  EXPECT_EQ(terms.diffuse.pixel(1)[3], 0.0f) << "the background's alpha";
}

TEST(ReferenceImage, InfOnlyWhereTheExactResultOverflowsFloat) {
  // Head-on light, eye above, kd = ks = 1, ka = 0: each channel is 2*Li (FLT_MAX ~ 3.40e38).
  // Li = 1e30 -> 2e30 finite; Li = 1.5e38 -> 3e38 finite although a float sum of the terms would
  // be close to the edge; Li = 2e38 -> 4e38 overflows -> +Inf. Exercise all three in one pixel.
  Scene scene = scene_with({0, 0, 5}, {point_light({0, 0, 5}, {1e30, 1.5e38, 2e38})});
  scene.materials = {material({0, 0, 0}, {1, 1, 1}, {1, 1, 1}, 8.0)};
  const Image image = reference_image(scene, row_gbuffer({0.0f}));
  EXPECT_NEAR(image.pixel(0)[0], 2e30f, 2e30 * 1e-6) << "Li=1e30: 2e30 stays finite";
  EXPECT_NEAR(image.pixel(0)[1], 3e38f, 3e38 * 1e-6) << "Li=1.5e38: 3e38 < FLT_MAX stays finite";
  EXPECT_TRUE(std::isinf(image.pixel(0)[2]) && image.pixel(0)[2] > 0)
      << "Li=2e38: 4e38 > FLT_MAX becomes +Inf";
  EXPECT_EQ(image.pixel(0)[3], 1.0f) << "overflowing pixel is still shaded";
}

}  // namespace
}  // namespace phongcl
