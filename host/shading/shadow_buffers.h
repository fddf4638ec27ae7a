#pragma once
// The scene's shadow geometry on the device (kernels/shadow_layout.h): what both the shadow culling
// and the kernels that trace shadow rays read.
#include <vector>

#include "cl/opencl.h"
#include "geometry/device_geometry.h"
#include "shading/device_layout.h"

namespace phongcl {

// The tables in one block (phong_shade's shadow_geometry), each also a sub-buffer for the kernels
// that take them one by one (shadow culling, the lab's shadow rays).
struct ShadowGeometryBuffers {
  cl::Buffer block;
  ShadowGeometryTables tables{};  // where each starts in the block
  cl::Buffer nodes, primitives, bounds, planes, depth;
  cl_uint node_count = 0, plane_count = 0;
};

// `depth`: the frame's depth plane for screen-space shadows (shading/screen_depth.h), else empty.
ShadowGeometryBuffers upload_shadow_geometry(const cl::Context& context, const DeviceGeometry& geometry,
                                             const std::vector<float>& depth = {});

// OpenCL has no empty buffers: an empty table becomes one zeroed element, which no count reaches.
template <typename T>
cl::Buffer table_buffer(const cl::Context& context, const std::vector<T>& table) {
  std::vector<T> copy = table.empty() ? std::vector<T>(1, T{}) : table;
  return cl::Buffer(context, copy.begin(), copy.end(), true);
}

}  // namespace phongcl
