#include "scene/camera_space.h"

#include <glm/gtc/matrix_transform.hpp>

namespace phongcl {

glm::dmat4 world_to_camera(const Camera& camera) { return glm::lookAt(camera.eye, camera.look_at, camera.up); }

Scene to_camera_space(const Scene& scene) {
  const glm::dmat4 view = world_to_camera(scene.camera);
  Scene moved = scene;
  for (Light& light : moved.lights) {
    light.position = glm::dvec3(view * glm::dvec4(light.position, 1.0));
    light.direction = glm::dvec3(view * glm::dvec4(light.direction, 0.0));  // rigid: no inverse transpose needed
  }
  for (AreaLight& light : moved.area_lights) {
    light.position = glm::dvec3(view * glm::dvec4(light.position, 1.0));
    light.direction = glm::dvec3(view * glm::dvec4(light.direction, 0.0));
    light.up = glm::dvec3(view * glm::dvec4(light.up, 0.0));
  }
  // The world's directions stay the world's: the lookup turns camera-space directions back.
  if (moved.environment) moved.environment->to_world = moved.environment->to_world * glm::transpose(glm::dmat3(view));
  moved.camera.eye = glm::dvec3(0.0);
  moved.camera.look_at = glm::dvec3(0.0, 0.0, -1.0);
  moved.camera.up = glm::dvec3(0.0, 1.0, 0.0);
  Object world;
  world.kind = Object::Kind::transform;
  world.matrix = view;
  world.children = scene.objects;
  moved.objects = {world};
  return moved;
}

}  // namespace phongcl
