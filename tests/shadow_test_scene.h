#pragma once
// The scene shadow tests shade and trace: a ground plane, a knot mesh (lab/peers/knot_mesh.h),
// spheres plain and under non-uniform transforms, a loose triangle, a wall with a light beyond it.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/glm.hpp>

#include "peers/knot_mesh.h"
#include "scene/scene.h"
#include "scene/transform.h"

namespace phongcl::testing {

inline double largest_magnitude(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// A scene that exercises every shape: a ground plane, a knot mesh, spheres plain and under
// non-uniform transforms, loose triangles; point lights and a directional one. `offset` moves
// everything (camera and lights too). The knot has 20 triangles per segment.
inline Scene shadow_test_scene(const std::filesystem::path& dir, const glm::dvec3& offset, int width, int height,
                               int knot_segments = 48) {
  Scene scene = knot_scene(dir, knot_segments, 10, 2);
  scene.camera.width = width;
  scene.camera.height = height;
  Object plane, wall, ball, squashed, triangle, everything;
  plane.kind = Object::Kind::plane;
  plane.normal = {0, 1, 0};
  plane.offset = -0.01;  // just under the ground triangles
  wall.kind = Object::Kind::plane;  // x = 4.5, with a light beyond it: only a plane blocks that light
  wall.normal = {-2, 0, 0};
  wall.offset = -9;
  ball.kind = Object::Kind::sphere;
  ball.center = {2.5, 0.8, 1.5};
  ball.radius = 0.8;
  squashed.kind = Object::Kind::transform;
  squashed.matrix = compose_transform({-2.8, 1.0, 1.8}, {30, 10, 50}, {1.4, 0.5, 0.8});
  squashed.children = {ball};
  squashed.children[0].center = {0, 0, 0};
  triangle.kind = Object::Kind::triangle;
  triangle.vertices = {glm::dvec3(-1, 0.5, 3), glm::dvec3(1, 0.5, 3.5), glm::dvec3(0, 2.5, 3.2)};
  everything.kind = Object::Kind::transform;
  everything.matrix = compose_transform(offset, {0, 0, 0}, {1, 1, 1});
  everything.children = scene.objects;
  everything.children.insert(everything.children.end(), {plane, wall, ball, squashed, triangle});
  scene.objects = {everything};
  scene.lights.push_back({LightType::directional, {}, {-0.4, -1.0, -0.3}, glm::dvec3(0.4)});
  scene.lights.push_back({LightType::point, {0.5, 0.3, 2.0}, {}, glm::dvec3(0.4)});  // low: long shadows, grazing rays
  scene.lights.push_back({LightType::point, {6.0, 2.0, 0.0}, {}, glm::dvec3(0.4)});  // behind the wall
  scene.camera.eye += offset;
  scene.camera.look_at += offset;
  for (Light& light : scene.lights) light.position += offset;
  return scene;
}

}  // namespace phongcl::testing
