// Area lights: a pixel on the emitter's plane and behind it, grazing (the emitter cut by the pixel's
// horizon), tiny (1e-4) and huge (1e4) emitters, and the specular rule at q from 0 to 1e6. The
// oracle is the reference's quadrature in double (reference_area.h) at twice its default order:
// there is no long double Lambert formula to hold the kernel's to, and the quadrature shares nothing
// with it. Its own error (below 1e-9 for E and for S at q <= 30) is far below every bound here.
#include "reference/reference_area.h"
#include "stability/case_builder.h"
#include "stability/catalogue.h"

namespace phongcl {

namespace {

constexpr int kOracleOrder = 96;

// Pixels at `positions` with `normals` (material 0) under one area light; the oracle from the
// quadrature, kd E + ks S per channel.
StabilityCase area_case(std::string name, std::string what, AreaLight light, double kd, double ks, double shininess,
                        const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals) {
  StabilityCase c;
  c.name = std::move(name);
  c.group = "area lights";
  c.what = std::move(what);
  c.scene = starting_scene(0.0, kd, ks, shininess);
  c.scene.area_lights.push_back(light);
  c.gbuffer = blank_gbuffer(static_cast<int>(positions.size()), 1, c.name);
  for (std::size_t i = 0; i < positions.size(); ++i) set_surface(c.gbuffer, i, positions[i], normals[i]);
  c.oracle = [light, kd, ks, shininess, positions, normals, eye = c.scene.camera.eye] {
    std::vector<ExactColor> values;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const glm::dvec3 p(positions[i]), n = glm::normalize(glm::dvec3(normals[i]));
      const glm::dvec3 v = glm::normalize(eye - p);
      const AreaIntegrals exact = reference_area_integrals(light, p, n, v, SpecularModel::phong, shininess, kOracleOrder);
      const long double value = kd * exact.irradiance + ks * exact.highlight;
      values.push_back({value, value, value});
    }
    return values;
  };
  c = complete(std::move(c));
  c.abs_floor = 1e-6;  // shading is linear in the light's colour, 1 here
  return c;
}

AreaLight area(AreaShape shape, glm::dvec3 position, glm::dvec3 direction, glm::dvec2 size) {
  AreaLight light;
  light.shape = shape;
  light.position = position;
  light.direction = direction;
  light.up = {0.0, 0.0, 1.0};
  light.size = size;
  return light;
}

// Five pixels on the floor y = -1 in front of the eye, normals from straight up to 80 degrees off.
const std::vector<glm::vec3> kFloor = {{0, -1, -3}, {0.5f, -1, -2.5f}, {-0.7f, -1, -3.4f}, {0.2f, -1, -4}, {1.1f, -1, -2.8f}};
const std::vector<glm::vec3> kTilted = {{0, 1, 0}, {0.3f, 1, 0.2f}, {-1, 1, 0.5f}, {2, 1, -1}, {5.6f, 1, 0.3f}};

std::vector<StabilityCase> diffuse_cases() {
  std::vector<StabilityCase> cases;
  // Lambert's formula in float: a few roundings per edge term of size O(1) (the geometry is scaled
  // to the distance first), which cancel to E; a clipped polygon adds the horizon's term.
  auto bounds = [](StabilityCase c, double precise, std::string why) {
    const bool approximated = precise > 1e-3;  // the cut disk's polygon: double has the same error
    c.expect = {approximated ? Expectation::within(precise, why) : double_expectation(), Expectation::within(precise, why),
                Expectation::within(approximated ? precise : 10 * precise, "relaxed math: " + why),
                Expectation::finite_only("positions and normals rounded to half (2^-11) move E by its derivative: no promise")};
    return c;
  };
  for (AreaShape shape : {AreaShape::rect, AreaShape::disk}) {
    const std::string name = to_string(shape);
    const AreaLight overhead = area(shape, {0.2, 1.0, -3.0}, {0.1, -1, 0.05}, {1.5, shape == AreaShape::rect ? 0.8 : 1.5});
    cases.push_back(bounds(area_case(name + " overhead", "floor pixels, normals up to 80 degrees off: some see it cut by their horizon",
                                     overhead, 1.0, 0.0, 1.0, kFloor, kTilted),
                           shape == AreaShape::rect ? 5e-5 : 3e-3,
                           shape == AreaShape::rect ? "Lambert's sum, clipped exactly: a few float roundings per edge"
                                                    : "a disk cut by the horizon is an area-matched 64-gon, not exact"));
    // The pixels' plane holds the emitter: h = 0, nothing (one-sided); and behind it.
    AreaLight on_plane = overhead;
    on_plane.position = {0.0, -1.0, -6.0};
    on_plane.direction = {0.0, 1.0, 0.0};
    cases.push_back(bounds(area_case(name + " on the pixels' plane", "emitter in the floor's plane: no light (h = 0)", on_plane, 1.0,
                                     0.0, 1.0, kFloor, {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}}),
                           1e-5, "exactly 0"));
    AreaLight behind = overhead;
    behind.direction = -behind.direction;
    cases.push_back(bounds(area_case(name + " behind", "pixels behind the emitting side: no light", behind, 1.0, 0.0, 1.0, kFloor, kTilted),
                           1e-5, "exactly 0"));
    // Grazing: an emitter standing on the floor, the floor normals tilted towards and away from it.
    const AreaLight wall = area(shape, {0.0, -0.4, -5.0}, {0.0, 0.0, 1.0}, {2.0, shape == AreaShape::rect ? 1.2 : 2.0});
    AreaLight standing = wall;
    standing.up = {0.0, 1.0, 0.0};
    cases.push_back(bounds(area_case(name + " grazing", "an emitter standing on the floor: the horizon cuts it for tilted normals",
                                     standing, 1.0, 0.0, 1.0, kFloor, {{0, 1, 0}, {0, 1, -0.1f}, {0, 1, 0.1f}, {0, 1, 1e-4f}, {0, 0.01f, -1}}),
                           shape == AreaShape::rect ? 5e-5 : 3e-3,
                           shape == AreaShape::rect ? "Lambert's sum, clipped exactly" : "the cut disk's 64-gon"));
    for (double size : {1e-4, 1e4}) {
      AreaLight scaled = overhead;
      scaled.size = glm::dvec2(size, shape == AreaShape::rect ? size / 2 : size);
      scaled.position = size < 1.0 ? glm::dvec3(0.2, 1.0, -3.0) : glm::dvec3(0.2, 5.0, -3.0);
      cases.push_back(bounds(area_case(name + " " + number(size) + " wide", size < 1 ? "tiny emitter 2 away: E = O(1e-9)"
                                                                                      : "huge emitter 6 above: nearly the half space",
                                       scaled, 1.0, 0.0, 1.0, kFloor, kTilted),
                             shape == AreaShape::rect ? 5e-5 : 3e-3,
                             size < 1 ? "far-field 2x2 Gauss rule (rect), closed form (disk)" : "Lambert's sum, O(1) terms"));
    }
  }
  return cases;
}

// S of Phong's lobe against the converged quadrature: Arvo's closed form at integer q up to 1024,
// the edge rule at non-integer q below 16 and the log-linear interpolation between integers above
// (phong_polygon.h), held to the 1e-3 of
// docs/shading.md; half-storage rounds the positions to 2^-11, which moves a narrow highlight by
// its slope: no promise. Beyond q = 1024 S is the 4x4 rule, and the oracle is not converged either
// (its lobe is narrower than its points).
std::vector<StabilityCase> specular_cases() {
  std::vector<StabilityCase> cases;
  const Expectation closed_form = Expectation::within(1e-3, "Arvo's closed form: float roundings of the recurrences");
  const Expectation half = Expectation::finite_only("positions rounded to half move a narrow highlight by its slope");
  auto specular_case = [&](std::string name, std::string what, AreaLight light, double q, const std::vector<glm::vec3>& positions,
                           const std::vector<glm::vec3>& normals) {
    StabilityCase c = area_case(std::move(name), std::move(what), light, 0.0, 1.0, q, positions, normals);
    c.expect = {closed_form, closed_form, closed_form, half};
    // The formula cancels terms of the size of the emitter's solid angle (0.05 to 0.15 sr here) down
    // to S: float keeps a few ulp of that, up to 1e-7, as absolute error where S is far smaller.
    c.abs_floor = 1e-4;
    if (q > 1024) {
      const Expectation measured = Expectation::finite_only("beyond q = 1024 S is a 4x4 Gauss rule: its error is printed, not bounded");
      c.expect = {measured, measured, measured, measured};
      c.reference = Expectation::finite_only("the oracle's S is not converged beyond q = 1e3");
    }
    cases.push_back(std::move(c));
  };
  const AreaLight rect = area(AreaShape::rect, {0.0, 1.0, -3.0}, {0.0, -1.0, 0.0}, {1.0, 0.6});
  const std::vector<glm::vec3> into = {{0, 1, 0}, {0.1f, 1, 0}, {0, 1, 0.2f}, {-0.2f, 1, 0}, {0, 1, -0.1f}};
  for (double q : {0.0, 1e-3, 0.5, 1.0, 7.5, 37.5, 100.0, 1000.0, 1e6})
    specular_case("rect specular q=" + number(q), "ks S only, mirror directions into the emitter", rect, q, kFloor, into);
  // Mirror directions along the emitter's plane: r.w = 0 crosses it, and the lobe is cut there.
  for (double q : {10.0, 2.5})
    specular_case("rect specular straddling r.w=0 q=" + number(q), "normals tilted so that r.w = 0 cuts the emitter", rect, q, kFloor,
                  {{0, 1, 1.5f}, {0, 1, 2}, {1.5f, 1, 0}, {-2, 1, 0.5f}, {0, 1, -2.5f}});
  // The eye sees the floor at grazing angles far away: r nearly along the floor.
  specular_case("rect specular grazing view", "floor pixels 40 to 200 away, the mirror direction 1-3 degrees up", rect, 100.0,
                {{0, -1, -40}, {1, -1, -80}, {-2, -1, -120}, {0.5f, -1, -160}, {0, -1, -200}},
                {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}});
  const AreaLight standing = [] {
    AreaLight wall = area(AreaShape::disk, {0.0, -0.4, -5.0}, {0.0, 0.0, 1.0}, {2.0, 2.0});
    wall.up = {0.0, 1.0, 0.0};
    return wall;
  }();
  for (double q : {0.0, 0.5, 10.0, 100.0})
    specular_case("disk specular straddling the horizon q=" + number(q), "an emitter standing on the floor, cut by tilted horizons",
                  standing, q, kFloor, {{0, 1, 0}, {0, 1, -0.1f}, {0, 1, 0.1f}, {0, 1, 1e-4f}, {0, 1, -0.3f}});
  for (double size : {1e-4, 1e4}) {
    AreaLight scaled = rect;
    scaled.size = glm::dvec2(size, size / 2);
    scaled.position = size < 1.0 ? glm::dvec3(0.0, 1.0, -3.0) : glm::dvec3(0.0, 5.0, -3.0);
    specular_case("rect specular " + number(size) + " wide", size < 1 ? "tiny emitter: S = O(1e-9)" : "huge emitter: the lobe's whole hemisphere",
                  scaled, 10.0, kFloor, into);
  }
  return cases;
}

}  // namespace

std::vector<StabilityCase> area_light_cases() {
  std::vector<StabilityCase> cases = diffuse_cases();
  for (StabilityCase& c : specular_cases()) cases.push_back(std::move(c));
  return cases;
}

}  // namespace phongcl
