#include "scene/transform.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace phongcl {

glm::dmat4 matrix_from_row_major(const std::vector<double>& values) {
  glm::dmat4 matrix(1.0);
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) matrix[column][row] = values.at(row * 4 + column);
  return matrix;
}

glm::dmat4 compose_transform(const glm::dvec3& translate, const glm::dvec3& rotate_deg,
                             const glm::dvec3& scale) {
  // Each glm call multiplies on the right, so the last one written is the first applied to a point.
  glm::dmat4 matrix = glm::translate(glm::dmat4(1.0), translate);
  matrix = glm::rotate(matrix, glm::radians(rotate_deg.z), glm::dvec3(0.0, 0.0, 1.0));
  matrix = glm::rotate(matrix, glm::radians(rotate_deg.y), glm::dvec3(0.0, 1.0, 0.0));
  matrix = glm::rotate(matrix, glm::radians(rotate_deg.x), glm::dvec3(1.0, 0.0, 0.0));
  return glm::scale(matrix, scale);
}

bool is_affine(const glm::dmat4& matrix) {
  return matrix[0][3] == 0.0 && matrix[1][3] == 0.0 && matrix[2][3] == 0.0 && matrix[3][3] == 1.0;
}

bool is_singular(const glm::dmat4& matrix) {
  const glm::dmat3 linear(matrix);
  const double bound = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
  return !(std::abs(glm::determinant(linear)) > 1e-12 * bound);
}

}  // namespace phongcl
