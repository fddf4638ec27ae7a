#include "reference/reference_screen_shadows.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phongcl {

namespace {

constexpr double kBias = 0x1p-9;
constexpr double kDirectionalEnd = 0x1p100;

}  // namespace

ReferenceScreenMarch::ReferenceScreenMarch(const Camera& camera, const GBuffer& gbuffer, int steps, double thickness)
    : eye_(camera.eye), steps_(steps), thickness_(thickness) {
  forward_ = glm::normalize(camera.look_at - camera.eye);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
  scale_ = camera.height / (2.0 * std::tan(camera.fov_y_deg * M_PI / 360.0));
  centre_x_ = camera.width / 2.0 - (gbuffer.data_window.x_min - gbuffer.display_window.x_min);
  centre_y_ = camera.height / 2.0 - (gbuffer.data_window.y_min - gbuffer.display_window.y_min);
  width_ = gbuffer.width;
  height_ = gbuffer.height;
  depth_.assign(gbuffer.pixel_count(), std::numeric_limits<double>::infinity());
  near_ = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
    const glm::dvec3 p(gbuffer.position[0][i], gbuffer.position[1][i], gbuffer.position[2][i]);
    depth_[i] = glm::dot(p - eye_, forward_);
    near_ = std::min(near_, depth_[i]);
    far_ = std::max(far_, depth_[i]);
  }
  near_ = std::max(near_ * 0.5, 1e-6 * far_);
}

glm::dvec2 ReferenceScreenMarch::project(const glm::dvec3& point) const {
  const double z = glm::dot(point, forward_);
  return {centre_x_ + scale_ * glm::dot(point, right_) / z, centre_y_ - scale_ * glm::dot(point, up_) / z};
}

double ReferenceScreenMarch::depth_at(int column, int row) const {
  column = std::clamp(column, 0, width_ - 1);
  row = std::clamp(row, 0, height_ - 1);
  return depth_[static_cast<std::size_t>(row) * width_ + column];
}

RayOutcome ReferenceScreenMarch::march(const ReferenceShadowRay& ray, double depth_slack, double pixel_slack) const {
  // In the eye's frame; the part of the ray in front of the camera between the frame's depths and
  // inside the image, each bound a linear inequality in t once multiplied by the positive depth.
  const glm::dvec3 o = ray.origin - eye_, d = ray.direction;
  const double z0 = glm::dot(o, forward_), dz = glm::dot(d, forward_);
  const double x0 = glm::dot(o, right_), dx = glm::dot(d, right_), y0 = glm::dot(o, up_), dy = glm::dot(d, up_);
  const double c0[6] = {z0 - near_, far_ - z0, centre_x_ * z0 + scale_ * x0, (width_ - centre_x_) * z0 - scale_ * x0,
                        centre_y_ * z0 - scale_ * y0, (height_ - centre_y_) * z0 + scale_ * y0};
  const double c1[6] = {dz, -dz, centre_x_ * dz + scale_ * dx, (width_ - centre_x_) * dz - scale_ * dx,
                        centre_y_ * dz - scale_ * dy, (height_ - centre_y_) * dz + scale_ * dy};
  double begin = 0.0, end = std::min(ray.t_max, kDirectionalEnd);
  for (int k = 0; k < 6; ++k) {
    if (c1[k] > 0.0) begin = std::max(begin, -c0[k] / c1[k]);
    else if (c1[k] < 0.0) end = std::min(end, -c0[k] / c1[k]);
    else if (c0[k] < 0.0) return RayOutcome::free;
  }
  if (!(begin < end)) return RayOutcome::free;
  const glm::dvec3 a = o + begin * d, b = o + end * d;
  const glm::dvec2 pa = project(a), pb = project(b);
  const double za = glm::dot(a, forward_), zb = glm::dot(b, forward_);
  const double pixels = glm::length(pb - pa);
  const double first = std::min(1.0, 1.0 / std::max(pixels, 1.0));
  const double step = (1.0 - first) / std::max(steps_ - 1, 1);
  const double thickness = thickness_ > 0.0 ? thickness_ : 2.0 * std::abs(zb - za) / steps_;
  bool borderline = false;
  for (int k = 0; k < steps_; ++k) {
    const double s = first + step * k;
    const double ray_depth = 1.0 / ((1.0 - s) / za + s / zb);
    const glm::dvec2 at = pa + s * (pb - pa);
    const auto decide = [&](double surface, bool& close) {
      const double deep = thickness_ < 0.0 ? -thickness_ * surface : thickness;
      const double near_bound = surface * (1.0 + kBias), far_bound = surface + deep;
      close = std::abs(ray_depth - near_bound) <= depth_slack * near_bound ||
              std::abs(ray_depth - far_bound) <= depth_slack * far_bound;
      return ray_depth > near_bound && ray_depth < far_bound;
    };
    bool close = false;
    const int column = static_cast<int>(std::floor(at.x)), row = static_cast<int>(std::floor(at.y));
    const bool hit = decide(depth_at(column, row), close);
    // A sample within the slack of a pixel's edge may be read from the pixel beside it.
    for (const auto& [dc, dr] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
      const double edge_distance = dc != 0 ? (dc < 0 ? at.x - column : column + 1 - at.x) : (dr < 0 ? at.y - row : row + 1 - at.y);
      bool ignored = false;
      if (edge_distance <= pixel_slack && decide(depth_at(column + dc, row + dr), ignored) != hit) close = true;
    }
    if (hit && !close) return RayOutcome::blocked;  // whatever the samples before it
    borderline = borderline || close;
  }
  return borderline ? RayOutcome::borderline : RayOutcome::free;
}

}  // namespace phongcl
