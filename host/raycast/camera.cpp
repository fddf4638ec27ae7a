#include "raycast/camera.h"

#include <cmath>

namespace phongcl {

bool Frustum::may_overlap_ball(const glm::dvec3& center, double radius) const {
  for (const glm::dvec3& normal : inward_normals)
    if (glm::dot(normal, center - apex) < -radius) return false;
  return true;
}

PerspectiveCamera::PerspectiveCamera(const Camera& camera)
    : eye_(camera.eye),
      forward_(glm::normalize(camera.look_at - camera.eye)),
      right_(glm::normalize(glm::cross(forward_, camera.up))),
      up_(glm::cross(right_, forward_)),
      half_height_(std::tan(glm::radians(camera.fov_y_deg) / 2.0)),
      width_(camera.width),
      height_(camera.height) {
  half_width_ = half_height_ * width_ / height_;  // square pixels
}

glm::dvec3 PerspectiveCamera::direction_through(double x, double y) const {
  // To [-1, 1]; image rows run downwards while up_ points up, hence the flip.
  const double screen_x = (x / width_) * 2.0 - 1.0;
  const double screen_y = 1.0 - (y / height_) * 2.0;
  return forward_ + (screen_x * half_width_) * right_ + (screen_y * half_height_) * up_;
}

Ray PerspectiveCamera::ray_through_pixel(int x, int y) const {
  return {eye_, glm::normalize(direction_through(x + 0.5, y + 0.5))};
}

Frustum PerspectiveCamera::frustum_through_pixels(int x_begin, int y_begin, int x_end, int y_end) const {
  // Corners in order around the block; each side plane holds two neighbouring corner rays.
  const std::array<glm::dvec3, 4> corners = {
      direction_through(x_begin, y_begin), direction_through(x_end, y_begin),
      direction_through(x_end, y_end), direction_through(x_begin, y_end)};
  const glm::dvec3 middle = direction_through((x_begin + x_end) / 2.0, (y_begin + y_end) / 2.0);
  Frustum frustum{eye_, {}};
  for (int side = 0; side < 4; ++side) {
    const glm::dvec3 normal = glm::normalize(glm::cross(corners[side], corners[(side + 1) % 4]));
    frustum.inward_normals[side] = glm::dot(normal, middle) >= 0.0 ? normal : -normal;
  }
  return frustum;
}

}  // namespace phongcl
