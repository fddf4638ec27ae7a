#pragma once
// A frame's shadow rays as the kernel makes them (kernels/shadow.h), one per shaded pixel facing
// each light, light after light: what the OpenCL traversal, the Embree peer and the double
// reference all trace, bit for bit the same rays.
#include <cstddef>

#include "peers/packed_frame.h"

namespace phongcl {

struct ShadowRaySet {
  std::size_t size = 0;  // slots: every light's frame, each padded to kPeerPadding
  AlignedVector<float> ox, oy, oz;  // origin - eye
  AlignedVector<float> dx, dy, dz;  // toward the light (not unit for point lights: t = 1 is the light)
  AlignedVector<float> t_max;       // <= 0: an empty slot (background, or facing away from the light)

  std::size_t traced() const;  // slots holding a ray
};

}  // namespace phongcl
