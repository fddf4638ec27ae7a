#pragma once
// The scene's shadow geometry on the device (kernels/shadow_layout.h): what both the shadow culling
// and the kernels that trace shadow rays read.
#include <vector>

#include "cl/opencl.h"
#include "geometry/device_geometry.h"

namespace phongcl {

struct ShadowGeometryBuffers {
  cl::Buffer nodes, primitives, bounds, planes;
  cl_uint node_count = 0, plane_count = 0;
};

ShadowGeometryBuffers upload_shadow_geometry(const cl::Context& context, const DeviceGeometry& geometry);

// OpenCL has no empty buffers: an empty table becomes one zeroed element, which no count reaches.
template <typename T>
cl::Buffer table_buffer(const cl::Context& context, const std::vector<T>& table) {
  std::vector<T> copy = table.empty() ? std::vector<T>(1, T{}) : table;
  return cl::Buffer(context, copy.begin(), copy.end(), true);
}

}  // namespace phongcl
