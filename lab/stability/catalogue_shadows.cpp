// Shadows at their limits (geometry mode): every case decides by hand, from the geometry, which
// lights reach which pixels, with margins far beyond rounding and the rays' offset (kernels/shadow.h).
#include <string>

#include "geometry/mesh_file.h"
#include "peers/knot_mesh.h"  // write_ply
#include "stability/case_builder.h"
#include "stability/catalogue.h"
#include "stability/gbuffer_builder.h"

namespace phongcl {

namespace {

struct ShadowPixel {
  glm::vec3 position, normal;
  std::vector<bool> lit;  // per light: reached (a light facing away adds nothing either way)
};

Object sphere(const glm::dvec3& center, double radius) { return {.kind = Object::Kind::sphere, .center = center, .radius = radius}; }
Object plane(const glm::dvec3& normal, double offset) { return {.kind = Object::Kind::plane, .normal = normal, .offset = offset}; }
Object triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return {.kind = Object::Kind::triangle, .vertices = {a, b, c}};
}
Object mesh(const std::filesystem::path& file) { return {.kind = Object::Kind::mesh, .file = file}; }

Light point_light(const glm::dvec3& position) { return {.position = position, .shadows = true}; }
Light directional_light(const glm::dvec3& direction) {
  return {.type = LightType::directional, .direction = direction, .shadows = true};
}

// The oracle with each pixel's unreached lights left out; the plain bounds (shadows are decided
// with margins, so only the shading's own rounding remains).
StabilityCase shadow_case(std::string name, std::string what, Scene scene, const std::vector<ShadowPixel>& pixels) {
  StabilityCase c;
  c.name = std::move(name);
  c.group = "shadows";
  c.what = std::move(what);
  c.scene = std::move(scene);
  c.gbuffer = blank_gbuffer(static_cast<int>(pixels.size()), 1, c.name);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    set_surface(c.gbuffer, i, pixels[i].position, pixels[i].normal);
    c.lit.push_back(pixels[i].lit);
    Scene reached = c.scene;
    reached.lights.clear();
    for (std::size_t k = 0; k < c.scene.lights.size(); ++k)
      if (pixels[i].lit.at(k)) reached.lights.push_back(c.scene.lights[k]);
    c.exact.push_back(exact_shade_pixel(reached, c.gbuffer, i));
  }
  c = complete(std::move(c));
  c.expect = {double_expectation(), precise_expectation(), fast_expectation(),
              half_expectation(c.gbuffer, 1.0, Expectation::within(2e-3, "positions and normals rounded to half (2^-11)"))};
  return c;
}

// The eye a few units from the pixels, as a camera would be (at the origin, the eye-relative
// coordinates and the rays' offset would vanish with a pixel's distance from it).
Scene lit_scene(std::vector<Object> objects, std::vector<Light> lights) {
  Scene scene = starting_scene(0.0, 0.8, 0.2, 16.0);
  scene.camera.eye = {0.0, 2.0, 10.0};
  scene.objects = std::move(objects);
  scene.lights = std::move(lights);
  return scene;
}

}  // namespace

std::vector<StabilityCase> shadow_cases(const std::filesystem::path& scratch) {
  std::vector<StabilityCase> cases;
  const glm::vec3 up(0, 1, 0);

  // A point light on the ground plane, another at a sphere's lowest point: rays that end exactly
  // on a surface stop short of it (by eps(L)) and are not blocked by it.
  cases.push_back(shadow_case(
      "light on a surface", "lights on the ground and on a sphere: rays end short of the surface they lie on",
      lit_scene({plane(up, 0), sphere({0, 1.5, 0}, 0.5)}, {point_light({3, 0, 0}), point_light({0, 1, 0})}),
      {{{0.3f, 1.1f, 0}, {0.6f, -0.8f, 0}, {true, true}},  // on the sphere, facing the ground light
       {{0.5f, 0, 0.2f}, up, {true, true}},                // the ground: in the plane of the first light, below the second
       {{-1, 0, 0}, up, {true, true}}}));

  // A sun 1e-3 radians above the horizon: rays along the ground clear it (they start eps above it
  // and rise), and a sphere on the ground casts a shadow 1000 times longer than it is high.
  cases.push_back(shadow_case(
      "grazing rays", "a sun 1e-3 rad above the ground: the ground never shadows itself; a sphere's long shadow",
      lit_scene({plane(up, 0), sphere({-3, 0.5, 0}, 0.5)}, {directional_light({1, -1e-3, 0})}),
      {{{0, 0, 0}, up, {false}},        // behind the sphere: the ray passes it 0.003 up, inside
       {{0, 0, 0.03f}, up, {false}},    // the sphere's section there is 0.055 wide
       {{0, 0, 0.49f}, up, {true}},
       {{0, 0, 2}, up, {true}},
       {{5, 0, -7}, up, {true}}}));

  // A point light at a sphere's centre: every ray from outside crosses the sphere; a point of its
  // inner surface facing the light is lit (the segment crosses no surface).
  cases.push_back(shadow_case(
      "light inside an object", "a light at a sphere's centre: blocked outside, lit on the inner surface",
      lit_scene({plane(up, 0), sphere({0, 2, 0}, 1)}, {point_light({0, 2, 0})}),
      {{{0, 0, 0}, up, {false}}, {{3, 0, 1}, up, {false}}, {{0, 1, 0}, up, {true}}, {{0, 2.8f, 0.6f}, {0, -0.8f, -0.6f}, {true}}}));

  // Two identical triangles as an occluder, and two identical triangles as the shaded surface:
  // the first block together, the second never block their own pixels.
  const glm::dvec3 a(-1, 1, -1), b(1, 1, -1), c(0, 1, 1), d(2, 0.5, -1), e(4, 0.5, -1), f(3, 0.5, 1);
  cases.push_back(shadow_case(
      "coincident triangles", "an occluder and a surface each made of two coincident triangles",
      lit_scene({plane(up, 0), triangle(a, b, c), triangle(a, b, c), triangle(d, e, f), triangle(d, e, f)},
                {point_light({0, 5, 0})}),
      {{{0, 0, 0}, up, {false}}, {{3, 0, -3}, up, {true}}, {{3, 0.5f, -1.0f / 3}, up, {true}}}));

  // Zero-area triangles (collinear, a repeated vertex, one point) between a light and the ground
  // block nothing; one real triangle of the same file does.
  TriangleMesh degenerate;
  degenerate.vertices = {{0, 1, -1}, {0, 1, 0}, {0, 1, 1}, {1, 2, 1}, {5, 1, -0.5f}, {6, 1, -0.5f}, {5.5f, 1, 0.5f}};
  degenerate.triangles = {{0, 1, 2}, {3, 3, 1}, {3, 3, 3}, {4, 5, 6}};
  write_ply(scratch / "degenerate.ply", degenerate);
  cases.push_back(shadow_case(
      "degenerate mesh", "zero-area triangles of a mesh block nothing, even a ray through one; its real triangle blocks",
      lit_scene({plane(up, 0), mesh(scratch / "degenerate.ply")}, {point_light({0, 5, 0}), point_light({5.5, 5, 0})}),
      {{{0, 0, 0.1f}, up, {true, true}}, {{5.5f, 0, -0.1f}, up, {true, false}}}));

  // A million triangles: a 1000 x 500 grid of quads over [-2, 2]^2 at height 1.
  TriangleMesh plate;
  constexpr int kColumns = 1000, kRows = 500;
  for (int j = 0; j <= kRows; ++j)
    for (int i = 0; i <= kColumns; ++i) plate.vertices.emplace_back(-2 + 4.0f * i / kColumns, 1, -2 + 4.0f * j / kRows);
  for (int j = 0; j < kRows; ++j) {
    for (int i = 0; i < kColumns; ++i) {
      const auto v = static_cast<std::uint32_t>(j * (kColumns + 1) + i);
      plate.triangles.push_back({v, v + 1, v + kColumns + 2});
      plate.triangles.push_back({v, v + kColumns + 2, v + kColumns + 1});
    }
  }
  write_ply(scratch / "plate.ply", plate);
  cases.push_back(shadow_case(
      "huge mesh: 1e6 triangles", "a plate of a million triangles over the ground",
      lit_scene({plane(up, 0), mesh(scratch / "plate.ply")}, {point_light({0, 5, 0})}),
      // (Pixels whose rays cross the plate at a grid vertex or line would test only the traversal's
      // handling of cracks; these cross mid-cell.)
      {{{0.0013f, 0, 0.0021f}, up, {false}}, {{1.873f, 0, 1.8371f}, up, {false}}, {{5, 0, 0}, up, {true}},
       {{0.5f, 1.5f, 0}, up, {true}}}));

  // A ceiling of one triangle 2e15 across, the pixels far inside it: float still holds its
  // products (about 1e31). (Near an edge of such a triangle, a float vertex is only known to 6e7,
  // so which side a ray passes is undecided there.)
  TriangleMesh ceiling;
  ceiling.vertices = {{-1e15f, 2, -1e15f}, {1e15f, 2, -1e15f}, {0, 2, 1e15f}};
  ceiling.triangles = {{0, 1, 2}};
  write_ply(scratch / "ceiling.ply", ceiling);
  cases.push_back(shadow_case(
      "huge mesh: 2e15 across", "a ceiling of one triangle 2e15 across, a light above it",
      lit_scene({mesh(scratch / "ceiling.ply")}, {point_light({0, 10, 0})}),
      {{{0.3f, 0, -0.7f}, up, {false}}, {{3, 1.9f, 0}, up, {false}}, {{1, 5, 0}, up, {true}}}));

  // A quad of two triangles over the ground shadows the same pixels at every size: level at height
  // 1 from half size 1e4 to 1e30 (from 1e19 the products of its float corners overflow), and
  // tilted by slopes 1/4 and 1/8 through (0, 1, 0) to 1e12 (from its float corners, the plane's
  // place near the eye moves by units at 1e8). The pixels are a sixth of a triangle's size from
  // any edge, lit by a light overhead and a low sun whose rays run mostly along x, so both cross
  // the quad's plane far from its corners.
  for (const char* half_size : {"1e4", "1e8", "1e12", "1e19", "1e30"}) {
    for (const bool tilted : {false, true}) {
      const double h = std::stod(half_size);
      if (tilted && h > 1e12) continue;
      const auto corner = [&](double x, double z) { return glm::dvec3(x, tilted ? 1 - x / 4 - z / 8 : 1, z); };
      const glm::dvec3 p0 = corner(-h / 2, -h), p1 = corner(h, -h), p2 = corner(h, h), p3 = corner(-h / 2, h);
      cases.push_back(shadow_case(
          std::string("huge occluder: ") + (tilted ? "tilted" : "level") + " quad of half size " + half_size,
          "a two-triangle quad over the ground shadows as a small one does, whatever its size",
          lit_scene({plane(up, 0), triangle(p0, p1, p2), triangle(p0, p2, p3)},
                    {point_light({0.3, 5, 0.2}), directional_light({-1, -0.4, 0.3})}),
          // (The tilted quad is at height 0.85 over the third and fourth pixels, and under the ground
          // at the fifth, which only the level one shadows.)
          {{{0, 0, 0}, up, {false, false}}, {{-2, 0, 1}, up, {false, false}}, {{0.5f, 0.5f, 0.2f}, up, {false, false}},
           {{0.5f, 2, 0.2f}, up, {true, true}}, {{6, 0, 4}, up, {tilted, tilted}}}));
    }
  }

  // A sphere on the ground a million units from the origin, the eye beside it: positions are
  // 0.0625 apart there and rays leave their surfaces eps = 2^-20 (|P - eye| + |eye|) = 1.4 units
  // out, so the pixels are well inside the shadow and well outside it.
  const glm::dvec3 far(1e6, 0, 1e6);
  Scene distant = lit_scene({plane(up, 0), sphere(far + glm::dvec3(0, 1, 0), 1)}, {point_light(far + glm::dvec3(0, 10, 0))});
  distant.camera.eye = far + glm::dvec3(0, 3, 10);
  const glm::vec3 at(far);
  cases.push_back(shadow_case("1e6 from the origin", "a sphere's shadow a million units from the origin", distant,
                              {{at, up, {false}}, {at + glm::vec3(0.5f, 0, 0.25f), up, {false}},
                               {at + glm::vec3(3, 0, 0), up, {true}}, {at + glm::vec3(0, 0, -4), up, {true}}}));
  return cases;
}

}  // namespace phongcl
