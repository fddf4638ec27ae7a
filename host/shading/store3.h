#pragma once
// Double vectors into the float fields of the structs host and kernel share (kernels/layout.h,
// kernels/shadow_layout.h).
#include <cstddef>

#include <glm/glm.hpp>

namespace phongcl {

// xyz as floats into a field of three, or of four with w unused (zeroed). The field is taken by
// reference so its size is known: through a pointer, the w of a field of three landed on the next
// member.
template <std::size_t N>
void store3(float (&out)[N], const glm::dvec3& value) {
  static_assert(N == 3 || N == 4, "store3 fills xyz, or xyz and an unused w");
  out[0] = static_cast<float>(value.x);
  out[1] = static_cast<float>(value.y);
  out[2] = static_cast<float>(value.z);
  if constexpr (N == 4) out[3] = 0.0f;
}

}  // namespace phongcl
