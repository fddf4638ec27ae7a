#pragma once
// The two ways a scene file states a transform, converted to GLM's column-major object-to-parent matrix.
#include <vector>

#include <glm/glm.hpp>

namespace phongcl {

// 16 numbers in reading order (row-major), as people write matrices; GLM indexes m[column][row].
glm::dmat4 matrix_from_row_major(const std::vector<double>& values);

// T * R * S, where R rotates about X first, then Y, then Z (angles in degrees).
glm::dmat4 compose_transform(const glm::dvec3& translate, const glm::dvec3& rotate_deg,
                             const glm::dvec3& scale);

bool is_affine(const glm::dmat4& matrix);  // last row 0, 0, 0, 1

// True if the linear part cannot be inverted reliably: its determinant is negligible against the
// product of its column lengths (Hadamard's bound), so uniform scale alone never trips it.
bool is_singular(const glm::dmat4& matrix);

}  // namespace phongcl
