#pragma once
// The scene file's pinhole camera: rays from the eye through pixel centres, and the pyramid of
// rays through a block of pixels (to cull objects once per block rather than once per ray).
#include <array>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace phongcl {

// origin + t * direction. World rays have unit directions; carried into a transform's object space
// the direction is left unnormalised, so t means the same distance in every space.
struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;
};

// An infinite pyramid from `apex` bounded by four planes through it.
struct Frustum {
  glm::dvec3 apex;
  std::array<glm::dvec3, 4> inward_normals;  // unit length

  // False only if the ball lies wholly outside; may be true for a ball that misses a corner.
  bool may_overlap_ball(const glm::dvec3& center, double radius) const;
};

class PerspectiveCamera {
 public:
  explicit PerspectiveCamera(const Camera& camera);

  // Through the centre of pixel (x, y); y = 0 is the top row, x = 0 the left column.
  Ray ray_through_pixel(int x, int y) const;
  // Holds every ray through the pixels x_begin <= x < x_end, y_begin <= y < y_end.
  Frustum frustum_through_pixels(int x_begin, int y_begin, int x_end, int y_end) const;

 private:
  // Unnormalised, through the image point (x, y) in pixel units: pixel (i, j) spans [i, i+1) x [j, j+1).
  glm::dvec3 direction_through(double x, double y) const;

  glm::dvec3 eye_;
  glm::dvec3 forward_, right_, up_;  // orthonormal; right_ is screen +x, up_ is screen up
  double half_width_, half_height_;  // of the image plane at distance 1
  int width_, height_;
};

}  // namespace phongcl
