#include "shading/shadow_buffers.h"

#include "cl/table_block.h"

namespace phongcl {

ShadowGeometryBuffers upload_shadow_geometry(const cl::Context& context, const DeviceGeometry& geometry,
                                             const std::vector<float>& depth) {
  TableBlockLayout layout(sub_buffer_alignment(context));
  ShadowGeometryBuffers buffers;
  buffers.tables = {.nodes = layout.add(geometry.nodes),
                    .primitives = layout.add(geometry.primitives),
                    .bounds = layout.add(geometry.bounds),
                    .planes = layout.add(geometry.planes),
                    .depth = layout.add(depth)};
  buffers.block = layout.upload(context, CL_MEM_READ_ONLY);
  buffers.nodes = layout.table(buffers.block, buffers.tables.nodes);
  buffers.primitives = layout.table(buffers.block, buffers.tables.primitives);
  buffers.bounds = layout.table(buffers.block, buffers.tables.bounds);
  buffers.planes = layout.table(buffers.block, buffers.tables.planes);
  buffers.depth = layout.table(buffers.block, buffers.tables.depth);
  buffers.node_count = static_cast<cl_uint>(geometry.nodes.size());
  buffers.plane_count = static_cast<cl_uint>(geometry.planes.size());
  return buffers;
}

}  // namespace phongcl
