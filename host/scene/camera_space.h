#pragma once
// Camera space, as renderers write "camera" or "view" G-buffers: the eye at the origin looking
// down -Z, +Y up, +X right (OpenGL's view space; glm::lookAt of the scene camera).
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace phongcl {

// World -> camera space for the scene file's camera (eye, look_at, up). A rigid motion.
glm::dmat4 world_to_camera(const Camera& camera);

// The same scene seen from camera space: lights (area lights too) moved and turned by world_to_camera, the camera
// put at the origin looking down -Z (same field of view and image size), and the objects wrapped
// in one transform so the generator produces a camera-space G-buffer.
Scene to_camera_space(const Scene& scene);

}  // namespace phongcl
