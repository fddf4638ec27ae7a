#pragma once
// The scene file's pinhole camera: rays from the eye through pixel centres.

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace phongcl {

// origin + t * direction. World rays have unit directions; carried into a transform's object space
// the direction is left unnormalised, so t means the same distance in every space.
struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;
};

class PerspectiveCamera {
 public:
  explicit PerspectiveCamera(const Camera& camera);

  // Through the centre of pixel (x, y); y = 0 is the top row, x = 0 the left column.
  Ray ray_through_pixel(int x, int y) const;

 private:
  // Unnormalised, through the image point (x, y) in pixel units: pixel (i, j) spans [i, i+1) x [j, j+1).
  glm::dvec3 direction_through(double x, double y) const;

  glm::dvec3 eye_;
  glm::dvec3 forward_, right_, up_;  // orthonormal; right_ is screen +x, up_ is screen up
  double half_width_, half_height_;  // of the image plane at distance 1
  int width_, height_;
};

}  // namespace phongcl
