#include "raycast/camera.h"

#include <cmath>

namespace phongcl {

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

}  // namespace phongcl
