#include "peers/knot_mesh.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>

#include <glm/gtc/constants.hpp>

namespace phongcl {
namespace {

// The (2, 3) torus knot and its first two derivatives, scaled to about 4 units across.
glm::dvec3 knot(double s) { return 0.7 * glm::dvec3((2 + std::cos(3 * s)) * std::cos(2 * s), std::sin(3 * s), (2 + std::cos(3 * s)) * std::sin(2 * s)); }
glm::dvec3 knot_d1(double s) {
  return 0.7 * glm::dvec3(-3 * std::sin(3 * s) * std::cos(2 * s) - 2 * (2 + std::cos(3 * s)) * std::sin(2 * s), 3 * std::cos(3 * s),
                          -3 * std::sin(3 * s) * std::sin(2 * s) + 2 * (2 + std::cos(3 * s)) * std::cos(2 * s));
}
glm::dvec3 knot_d2(double s) { return (knot_d1(s + 1e-4) - knot_d1(s - 1e-4)) / 2e-4; }

template <typename T>
void put(std::ofstream& out, T value) {
  static_assert(std::endian::native == std::endian::little, "PLY is written little-endian");
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

TriangleMesh trefoil_knot(int segments, int sides) {
  if (segments < 3 || sides < 3) throw std::invalid_argument("a knot needs at least 3 segments and 3 sides");
  TriangleMesh mesh;
  const double tube = 0.32, lift = 2.2;
  for (int i = 0; i < segments; ++i) {
    const double s = 2 * glm::pi<double>() * i / segments;
    // Frenet frame: the knot's curvature never vanishes.
    const glm::dvec3 tangent = glm::normalize(knot_d1(s));
    const glm::dvec3 binormal = glm::normalize(glm::cross(knot_d1(s), knot_d2(s)));
    const glm::dvec3 normal = glm::cross(binormal, tangent);
    for (int j = 0; j < sides; ++j) {
      const double a = 2 * glm::pi<double>() * j / sides;
      const glm::dvec3 p = knot(s) + tube * (std::cos(a) * normal + std::sin(a) * binormal) + glm::dvec3(0, lift, 0);
      mesh.vertices.emplace_back(p);
    }
  }
  auto index = [&](int i, int j) { return static_cast<std::uint32_t>((i % segments) * sides + j % sides); };
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j) {
      mesh.triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      mesh.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  return mesh;
}

void write_ply(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::ofstream out(file, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const glm::vec3& v : mesh.vertices) {
    put(out, v.x);
    put(out, v.y);
    put(out, v.z);
  }
  for (const auto& triangle : mesh.triangles) {
    put(out, std::uint8_t{3});
    for (std::uint32_t corner : triangle) put(out, static_cast<std::int32_t>(corner));
  }
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write the mesh");
}

Scene knot_scene(const std::filesystem::path& directory, int segments, int sides, int lights) {
  const std::filesystem::path file = directory / "knot.ply";
  write_ply(file, trefoil_knot(segments, sides));
  Scene scene;
  scene.source = directory / "knot.json";
  scene.camera.eye = {0.0, 5.5, 9.0};
  scene.camera.look_at = {0.0, 1.6, 0.0};
  scene.camera.fov_y_deg = 45.0;
  scene.ambient = glm::dvec3(0.05);
  scene.materials = {{"ground", glm::dvec3(0.4), glm::dvec3(0.6), glm::dvec3(0.05), 8.0},
                     {"knot", glm::dvec3(0.5, 0.2, 0.1), glm::dvec3(0.8, 0.35, 0.15), glm::dvec3(0.5), 48.0}};
  Object ground_a, ground_b, tube;
  ground_a.kind = ground_b.kind = Object::Kind::triangle;
  ground_a.vertices = {glm::dvec3(-20, 0, -20), glm::dvec3(-20, 0, 20), glm::dvec3(20, 0, 20)};
  ground_b.vertices = {glm::dvec3(-20, 0, -20), glm::dvec3(20, 0, 20), glm::dvec3(20, 0, -20)};
  tube.kind = Object::Kind::mesh;
  tube.file = file;
  tube.material = 1;
  scene.objects = {ground_a, ground_b, tube};
  for (int k = 0; k < lights; ++k) {
    const double angle = 2 * glm::pi<double>() * (k + 0.3) / lights;
    Light light;
    light.position = {7.0 * std::cos(angle), 8.0 + k % 3, 7.0 * std::sin(angle)};
    light.color = glm::dvec3(1.2 / lights);
    light.shadows = true;
    scene.lights.push_back(light);
  }
  return scene;
}

}  // namespace phongcl
