// The G-buffer generator against analytic answers: the camera rays are re-derived here from the
// camera's definition (u, v, w basis, as in MIT 6.837) and intersected in closed form.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "raycast/raycast.h"
#include "scene/scene.h"
#include "common/error.h"
#include "raycast/depth_reconstruction.h"
#include "renderer_files.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using namespace testing;

// The G-buffer stores floats (relative rounding 6e-8) of doubles computed in a different order
// from the ones below (differences near 1e-15); 1e-5 of the value, or of 1 near zero, is far above
// both and far below any real mistake (a wrong pixel shifts hits by ~1e-2 in these scenes).
constexpr double kTolerance = 1e-5;

struct TestRay {
  glm::dvec3 origin, direction;
};

TestRay expected_ray(const Camera& camera, int x, int y) {
  const glm::dvec3 w = glm::normalize(camera.eye - camera.look_at);  // the camera looks down -w
  const glm::dvec3 u = glm::normalize(glm::cross(camera.up, w));     // image right
  const glm::dvec3 v = glm::cross(w, u);                              // image up
  const double tan_half_fov = std::tan(camera.fov_y_deg * M_PI / 360.0);
  const double aspect = static_cast<double>(camera.width) / camera.height;
  const double right = (2.0 * (x + 0.5) / camera.width - 1.0) * tan_half_fov * aspect;
  const double up = (1.0 - 2.0 * (y + 0.5) / camera.height) * tan_half_fov;  // row 0 is the top
  return {camera.eye, glm::normalize(right * u + up * v - w)};
}

// Smallest positive root of a t^2 + b t + c = 0.
std::optional<double> nearest_root(double a, double b, double c) {
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0) return std::nullopt;
  const double near = (-b - std::sqrt(discriminant)) / (2.0 * a);
  const double far = (-b + std::sqrt(discriminant)) / (2.0 * a);
  if (near > 0.0) return near;
  if (far > 0.0) return far;
  return std::nullopt;
}

struct Pixel {
  glm::dvec3 position, normal;
  float material;
};

Pixel pixel_at(const GBuffer& gbuffer, int x, int y) {
  const std::size_t i = static_cast<std::size_t>(y) * gbuffer.width + x;
  return {{gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]},
          {gbuffer.normal[0][i], gbuffer.normal[1][i], gbuffer.normal[2][i]},
          gbuffer.material[i]};
}

void expect_close(const glm::dvec3& actual, const glm::dvec3& expected, const char* what, int x, int y) {
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_LE(std::abs(actual[axis] - expected[axis]), kTolerance * std::max(1.0, std::abs(expected[axis])))
        << what << "[" << axis << "] at pixel (" << x << ", " << y << "): got " << actual[axis] << ", expected "
        << expected[axis];
}

struct AnalyticHit {
  glm::dvec3 position, normal;
};

// Every pixel against `analytic`, the closed-form hit of the pixel's ray (or none): that hit with
// `material`, or background where there is none. Returns how many pixels hit.
int expect_every_pixel(const Scene& scene, const GBuffer& gbuffer, float material,
                       const std::function<std::optional<AnalyticHit>(const TestRay&)>& analytic) {
  int hits = 0;
  for (int y = 0; y < gbuffer.height; ++y)
    for (int x = 0; x < gbuffer.width; ++x) {
      const Pixel pixel = pixel_at(gbuffer, x, y);
      const std::optional<AnalyticHit> hit = analytic(expected_ray(scene.camera, x, y));
      if (!hit) {
        EXPECT_EQ(pixel.material, -1.0f) << "at pixel (" << x << ", " << y << ")";
        continue;
      }
      ++hits;
      EXPECT_EQ(pixel.material, material) << "at pixel (" << x << ", " << y << ")";
      expect_close(pixel.position, hit->position, "P", x, y);
      expect_close(pixel.normal, hit->normal, "N", x, y);
    }
  return hits;
}

Scene scene_with(std::vector<Object> objects, int materials = 3) {
  Scene scene;
  scene.camera.eye = {0.0, 0.0, 5.0};
  scene.camera.width = 64;
  scene.camera.height = 48;
  scene.materials.resize(materials);
  scene.objects = std::move(objects);
  return scene;
}

Object sphere(glm::dvec3 center, double radius, int material) {
  Object object;
  object.kind = Object::Kind::sphere;
  object.center = center;
  object.radius = radius;
  object.material = material;
  return object;
}

TEST(Raycast, GbufferCoversTheImage) {
  const GBuffer gbuffer = generate_gbuffer(scene_with({}));
  EXPECT_EQ(gbuffer.width, 64);
  EXPECT_EQ(gbuffer.height, 48);
  for (const PixelWindow& window : {gbuffer.data_window, gbuffer.display_window}) {
    EXPECT_EQ(window.x_min, 0);
    EXPECT_EQ(window.y_min, 0);
    EXPECT_EQ(window.x_max, 63);
    EXPECT_EQ(window.y_max, 47);
  }
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(gbuffer.position[axis].size(), 64u * 48u);
    EXPECT_EQ(gbuffer.normal[axis].size(), 64u * 48u);
  }
  EXPECT_EQ(gbuffer.material.size(), 64u * 48u);
  EXPECT_FALSE(gbuffer.has_per_pixel_kd());
}

// Every pixel: the analytic hit where there is one, background where there is none.
TEST(Raycast, SphereHitsMatchTheAnalyticIntersection) {
  const glm::dvec3 center(0.3, -0.2, 0.5);
  const double radius = 1.1;
  Scene scene = scene_with({sphere(center, radius, 2)});
  scene.camera.eye = {0.5, 1.0, 6.0};
  scene.camera.look_at = {0.0, 0.2, 0.0};
  const GBuffer gbuffer = generate_gbuffer(scene);
  const int hits = expect_every_pixel(scene, gbuffer, 2.0f, [&](const TestRay& ray) -> std::optional<AnalyticHit> {
    const glm::dvec3 to_origin = ray.origin - center;
    const auto t =
        nearest_root(1.0, 2.0 * glm::dot(to_origin, ray.direction), glm::dot(to_origin, to_origin) - radius * radius);
    if (!t) return std::nullopt;
    const glm::dvec3 hit = ray.origin + *t * ray.direction;
    return AnalyticHit{hit, (hit - center) / radius};
  });
  EXPECT_GT(hits, 100);  // the sphere fills a good part of the image
}

TEST(Raycast, MissesAreBackground) {
  const GBuffer gbuffer = generate_gbuffer(scene_with({sphere({0, 0, 0}, 1.0, 1)}));
  for (auto [x, y] : {std::pair{0, 0}, {63, 0}, {0, 47}, {63, 47}, {5, 24}}) {
    const Pixel pixel = pixel_at(gbuffer, x, y);
    EXPECT_EQ(pixel.material, -1.0f) << "at (" << x << ", " << y << ")";
    EXPECT_EQ(pixel.position, glm::dvec3(0.0));
    EXPECT_EQ(pixel.normal, glm::dvec3(0.0));
  }
}

TEST(Raycast, PlaneHitFacesTheViewerFromEitherSide) {
  Object floor;
  floor.kind = Object::Kind::plane;
  floor.normal = {0.0, 2.0, 0.0};  // not unit: the plane is dot(normalize(normal), x) == offset
  floor.offset = -1.0;
  floor.material = 1;
  for (double eye_height : {3.0, -4.0}) {
    Scene scene = scene_with({floor});
    scene.camera.eye = {0.0, eye_height, 5.0};
    scene.camera.look_at = {0.0, -1.0, 0.0};
    const GBuffer gbuffer = generate_gbuffer(scene);
    for (auto [x, y] : {std::pair{32, 24}, {10, 40}, {50, 8}}) {
      const TestRay ray = expected_ray(scene.camera, x, y);
      const double t = (-1.0 - ray.origin.y) / ray.direction.y;
      ASSERT_GT(t, 0.0);
      const Pixel pixel = pixel_at(gbuffer, x, y);
      EXPECT_EQ(pixel.material, 1.0f);
      expect_close(pixel.position, ray.origin + t * ray.direction, "P", x, y);
      expect_close(pixel.normal, {0.0, eye_height > -1.0 ? 1.0 : -1.0, 0.0}, "N", x, y);
    }
  }
}

TEST(Raycast, TriangleHitInsideAndMissOutside) {
  Object triangle;
  triangle.kind = Object::Kind::triangle;
  // Clockwise seen from the camera, so its winding normal (0, 0, -1) must be flipped to face it.
  triangle.vertices = {glm::dvec3(-1, -1, 0), glm::dvec3(0, 1, 0), glm::dvec3(1, -1, 0)};
  triangle.material = 0;
  const Scene scene = scene_with({triangle});
  const GBuffer gbuffer = generate_gbuffer(scene);

  const int x = 33, y = 26;  // just right of and below the centre: inside
  const TestRay ray = expected_ray(scene.camera, x, y);
  const double t = -ray.origin.z / ray.direction.z;
  const Pixel inside = pixel_at(gbuffer, x, y);
  EXPECT_EQ(inside.material, 0.0f);
  expect_close(inside.position, ray.origin + t * ray.direction, "P", x, y);
  expect_close(inside.normal, {0.0, 0.0, 1.0}, "N", x, y);
  // Near the apex's height but well to the side: outside the triangle.
  EXPECT_EQ(pixel_at(gbuffer, 40, 14).material, -1.0f);
}

TEST(Raycast, TransformedSphereUsesTheInverseTransposeForNormals) {
  // An ellipsoid: the unit sphere scaled by (2, 0.5, 1), then moved by (0.5, 0.25, 0).
  const glm::dvec3 scale(2.0, 0.5, 1.0), translate(0.5, 0.25, 0.0);
  Object transform;
  transform.kind = Object::Kind::transform;
  transform.matrix = glm::scale(glm::translate(glm::dmat4(1.0), translate), scale);
  transform.children = {sphere({0, 0, 0}, 1.0, 1)};
  const Scene scene = scene_with({transform});
  const GBuffer gbuffer = generate_gbuffer(scene);
  const int hits = expect_every_pixel(scene, gbuffer, 1.0f, [&](const TestRay& ray) -> std::optional<AnalyticHit> {
    // Solve sum(((o + t d - translate) / scale)^2) == 1.
    const glm::dvec3 o = (ray.origin - translate) / scale, d = ray.direction / scale;
    const auto t = nearest_root(glm::dot(d, d), 2.0 * glm::dot(o, d), glm::dot(o, o) - 1.0);
    if (!t) return std::nullopt;
    const glm::dvec3 hit = ray.origin + *t * ray.direction;
    // The gradient of the implicit function, not the scaled sphere normal M * n.
    return AnalyticHit{hit, glm::normalize((hit - translate) / (scale * scale))};
  });
  EXPECT_GT(hits, 100);
}

TEST(Raycast, NearestHitWinsWhateverTheOrder) {
  const Object far_sphere = sphere({0, 0, -3}, 2.0, 0);
  const Object near_sphere = sphere({0, 0, 1}, 0.5, 1);
  for (const auto& objects : {std::vector{far_sphere, near_sphere}, std::vector{near_sphere, far_sphere}}) {
    const GBuffer gbuffer = generate_gbuffer(scene_with(objects));
    const Pixel centre = pixel_at(gbuffer, 32, 24);
    EXPECT_EQ(centre.material, 1.0f);
    EXPECT_NEAR(centre.position.z, 1.5, 0.01);  // the near sphere's front, not the far one's at -1
    EXPECT_EQ(pixel_at(gbuffer, 32, 12).material, 0.0f);  // beside the small sphere, the big one
  }
}

TEST(Raycast, EyeInsideASphereSeesItsInsideFacingBack) {
  Scene scene = scene_with({sphere({0, 0, 0}, 10.0, 0)});
  const GBuffer gbuffer = generate_gbuffer(scene);
  for (auto [x, y] : {std::pair{0, 0}, {32, 24}, {63, 47}}) {
    const TestRay ray = expected_ray(scene.camera, x, y);
    const Pixel pixel = pixel_at(gbuffer, x, y);
    EXPECT_EQ(pixel.material, 0.0f);
    EXPECT_NEAR(glm::length(pixel.position), 10.0, 1e-4);
    EXPECT_LT(glm::dot(pixel.normal, ray.direction), 0.0) << "at (" << x << ", " << y << ")";
  }
}

// Many small spheres spread over the image, so that pixel blocks cull different sets: every pixel
// must still find the nearest sphere a brute-force search over all of them finds.
TEST(Raycast, CullingByPixelBlocksLosesNoHits) {
  std::mt19937 random(6502);
  std::uniform_real_distribution<double> across(-2.5, 2.5), depth(-3.0, 1.0), size(0.05, 0.4);
  std::vector<Object> spheres;
  for (int i = 0; i < 60; ++i)
    spheres.push_back(sphere({across(random), across(random) * 0.7, depth(random)}, size(random), i % 3));
  Scene scene = scene_with(spheres);
  scene.camera.width = 100;  // not a multiple of the block size: partial blocks at the edges
  scene.camera.height = 70;
  const GBuffer gbuffer = generate_gbuffer(scene);

  int hits = 0;
  for (int y = 0; y < gbuffer.height; ++y)
    for (int x = 0; x < gbuffer.width; ++x) {
      const TestRay ray = expected_ray(scene.camera, x, y);
      std::optional<double> nearest_t;
      const Object* nearest = nullptr;
      for (const Object& s : spheres) {
        const glm::dvec3 to_origin = ray.origin - s.center;
        const auto t = nearest_root(1.0, 2.0 * glm::dot(to_origin, ray.direction),
                                    glm::dot(to_origin, to_origin) - s.radius * s.radius);
        if (t && (!nearest_t || *t < *nearest_t)) {
          nearest_t = t;
          nearest = &s;
        }
      }
      const Pixel pixel = pixel_at(gbuffer, x, y);
      ASSERT_EQ(pixel.material >= 0.0f, nearest_t.has_value()) << "at pixel (" << x << ", " << y << ")";
      if (!nearest_t) continue;
      ++hits;
      const glm::dvec3 hit = ray.origin + *nearest_t * ray.direction;
      EXPECT_EQ(pixel.material, static_cast<float>(nearest->material)) << "at pixel (" << x << ", " << y << ")";
      expect_close(pixel.position, hit, "P", x, y);
      expect_close(pixel.normal, (hit - nearest->center) / nearest->radius, "N", x, y);
    }
  EXPECT_GT(hits, 500);
}

// Row 0 is the top of the image: something above the look-at point lands in small y, and
// something to the right (+x, camera looking down -z with +y up) in large x.
TEST(Raycast, ImageRowsRunDownAndColumnsRight) {
  const GBuffer above = generate_gbuffer(scene_with({sphere({0, 1.2, 0}, 0.3, 0)}));
  const GBuffer right = generate_gbuffer(scene_with({sphere({1.6, 0, 0}, 0.3, 0)}));
  int hits_above = 0, hits_right = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      if (pixel_at(above, x, y).material >= 0.0f) {
        ++hits_above;
        EXPECT_LT(y, 24) << "hit at (" << x << ", " << y << ")";
      }
      if (pixel_at(right, x, y).material >= 0.0f) {
        ++hits_right;
        EXPECT_GE(x, 32) << "hit at (" << x << ", " << y << ")";
      }
    }
  EXPECT_GT(hits_above, 0);
  EXPECT_GT(hits_right, 0);
}

// Reconstructed positions against the position pass they replace. Float rounding, per coordinate:
// the stored depth carries 2^-24 relative error (so t * 2^-24 along the ray), the written and the
// rebuilt positions 2^-24 * |P| each; the ray itself is double. Allowing twice the sum:
// |error| <= 2^-23 * (depth + 2 * max|P|). A wrong convention or pixel-centre offset errs by far
// more (1/cos of the off-axis angle, or a pixel's footprint at that distance).
void expect_positions_from_depth(const GBuffer& rebuilt, const GBuffer& truth, const Plane& depth) {
  for (std::size_t i = 0; i < truth.pixel_count(); ++i) {
    if (!shaded(truth, i)) continue;
    const float largest = std::max({std::abs(truth.position[0][i]), std::abs(truth.position[1][i]), std::abs(truth.position[2][i])});
    const double tolerance = std::ldexp(1.0, -23) * (std::abs(depth[i]) + 2.0 * largest);
    for (int c = 0; c < 3; ++c)
      ASSERT_LE(std::abs(rebuilt.position[c][i] - truth.position[c][i]), tolerance)
          << "pixel " << i << " axis " << c << ": rebuilt " << rebuilt.position[c][i] << ", true " << truth.position[c][i];
  }
}

TEST(DepthReconstruction, BothConventionsMatchThePositionPass) {
  TempDir dir;
  auto [scene, g] = default_scene();
  // A crop of the camera's image: data window pixel (x, y) must still get the camera's ray (x, y).
  GBuffer crop = g;
  const PixelWindow window{20, 10, 80, 50};
  crop.data_window = window;
  crop.width = window.width();
  crop.height = window.height();
  const int width = g.width;  // clang 14 cannot capture a structured binding
  const auto crop_plane = [&](const Plane& plane) {
    Plane out;
    for (int y = window.y_min; y <= window.y_max; ++y)
      for (int x = window.x_min; x <= window.x_max; ++x) out.push_back(plane[static_cast<std::size_t>(y) * width + x]);
    return out;
  };
  for (int c = 0; c < 3; ++c) crop.position[c] = crop_plane(g.position[c]), crop.normal[c] = crop_plane(g.normal[c]);
  crop.material = crop_plane(g.material);

  for (const GBuffer* truth : {&g, &crop}) {
    for (auto [kind, convention] : {std::pair{DepthPass::distance, DepthConvention::distance},
                                    std::pair{DepthPass::view_z, DepthConvention::view_z}}) {
      SCOPED_TRACE(std::string(kind == DepthPass::distance ? "distance" : "view z") + (truth == &crop ? ", cropped" : ""));
      write_file(dir / "d.exr", *truth, blender_channels(scene, *truth, {.position = false, .depth = kind, .colors = false}));
      GBufferRead read = read_gbuffer(dir / "d.exr", {});
      ASSERT_TRUE(read.needs_positions_from_depth());
      EXPECT_NE(read.description.find("Depth"), std::string::npos) << read.description;
      positions_from_depth(read.gbuffer, read.depth, scene.camera, convention);
      expect_positions_from_depth(read.gbuffer, *truth, read.depth);
      expect_same_gbuffer(read.gbuffer, *truth, 1e-5);  // normals and materials untouched
    }
  }
}

TEST(DepthReconstruction, TheConventionsDifferOffAxis) {
  // Guards the test above against passing for either convention: the wrong one must fail it.
  auto [scene, g] = default_scene();
  GBuffer rebuilt = g;
  positions_from_depth(rebuilt, depth_pass(scene, g, DepthPass::distance), scene.camera, DepthConvention::view_z);
  double worst = 0.0;
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    if (shaded(g, i)) worst = std::max(worst, static_cast<double>(std::abs(rebuilt.position[0][i] - g.position[0][i])));
  EXPECT_GT(worst, 1e-2);
}

TEST(DepthReconstruction, DisplayWindowMustBeTheCameraImage) {
  auto [scene, g] = default_scene();
  g.source = "small.exr";
  scene.camera.width += 1;
  try {
    positions_from_depth(g, Plane(g.pixel_count(), 1.0f), scene.camera, DepthConvention::distance);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("small.exr: display window is 97x61 but the scene camera is 98x61"),
              std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace phongcl
