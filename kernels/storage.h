/* How the G-buffer planes are stored on the device, for phong.cl and cull.cl: float, or half with
 * HALF_STORAGE (half the bytes moved; vload_half converts to float). Plane k of a tile starts at
 * k * stride values (layout.h). */
#ifndef PHONGCL_STORAGE_H
#define PHONGCL_STORAGE_H

#include "phong_math.h"

#ifndef HALF_STORAGE
#error "storage.h needs HALF_STORAGE defined, 0 or 1"
#endif

#if HALF_STORAGE
#define STORAGE half
#else
#define STORAGE float
#endif

/* Values [group * PHONGCL_LANES, (group + 1) * PHONGCL_LANES) of plane `plane`. */
static inline floatv load_plane(__global const STORAGE* planes, uint stride, int plane, size_t group) {
#if HALF_STORAGE
  return VLOAD_HALF(group, planes + (size_t)plane * stride);
#else
  return VLOAD(group, planes + (size_t)plane * stride);
#endif
}

#endif
