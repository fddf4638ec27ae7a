#include "shading/shadow_buffers.h"

namespace phongcl {

ShadowGeometryBuffers upload_shadow_geometry(const cl::Context& context, const DeviceGeometry& geometry) {
  return {table_buffer(context, geometry.nodes), table_buffer(context, geometry.primitives),
          table_buffer(context, geometry.bounds), table_buffer(context, geometry.planes),
          static_cast<cl_uint>(geometry.nodes.size()), static_cast<cl_uint>(geometry.planes.size())};
}

}  // namespace phongcl
