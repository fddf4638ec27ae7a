#include "shading/shadow_culling.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "cl/kernel_source.h"

namespace phongcl {

ShadowCuller::ShadowCuller(const ComputeContext& compute, ProgramCache& cache, const std::string& bounds_options)
    : compute_(compute),
      bounds_program_(cache.build(compute, load_kernel_source("cull.cl"), bounds_options).program),
      cull_program_(cache.build(compute, load_kernel_source("shadow_cull.cl"), "-cl-std=CL1.2").program) {}

void ShadowCuller::level(ShadowLists& lists, const cl::Buffer& boxes, cl_uint limit, const CullLevel& where,
                         const ShadowLists* parent, const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                         std::size_t light_count, float offset_scale, float eye_extent, ShadowCullingStats& stats) {
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t pairs = static_cast<std::size_t>(lists.tiles) * light_count;
  const cl::Buffer none(context, CL_MEM_READ_ONLY, sizeof(ShadowCandidate));
  const cl::Buffer& parent_counts = parent ? parent->counts : none;
  const cl::Buffer& parent_offsets = parent ? parent->offsets : none;
  const cl::Buffer& parent_candidates = parent ? parent->candidates : none;
  lists.counts = cl::Buffer(context, CL_MEM_READ_WRITE, std::max<std::size_t>(pairs, 1) * sizeof(cl_uint));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_float, cl_float, cl_uint, CullLevel, cl::Buffer, cl::Buffer, cl::Buffer,
                    cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer>
      count(cull_program_, "count_shadow_candidates");
  const cl::Event counted = count(cl::EnqueueArgs(queue, cl::NDRange(pairs)), boxes, lists.tiles, lights, offset_scale,
                                  eye_extent, limit, where, parent_counts, parent_offsets, parent_candidates, geometry.nodes,
                                  geometry.node_count, geometry.bounds, geometry.planes, geometry.plane_count, lists.counts);
  std::vector<cl_uint> counts(pairs), offsets(pairs);
  queue.enqueueReadBuffer(lists.counts, CL_TRUE, 0, pairs * sizeof(cl_uint), counts.data());
  // Offsets: an exclusive prefix sum of the counts, on the host; pairs beyond the limit take none.
  const auto prefix_start = std::chrono::steady_clock::now();
  std::size_t total = 0;
  for (std::size_t p = 0; p < pairs; ++p) {
    offsets[p] = static_cast<cl_uint>(total);
    if (counts[p] == PHONGCL_SHADOW_TRAVERSE) ++stats.traversing;
    else total += counts[p];
  }
  lists.offsets = table_buffer(context, offsets);
  stats.culling_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - prefix_start).count();
  lists.candidates = cl::Buffer(context, CL_MEM_READ_WRITE, std::max<std::size_t>(total, 1) * sizeof(ShadowCandidate));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_float, cl_float, CullLevel, cl::Buffer, cl::Buffer, cl::Buffer,
                    cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl::Buffer>
      fill(cull_program_, "fill_shadow_candidates");
  const cl::Event filled = fill(cl::EnqueueArgs(queue, cl::NDRange(pairs)), boxes, lists.tiles, lights, offset_scale,
                                eye_extent, where, parent_counts, parent_offsets, parent_candidates, geometry.nodes,
                                geometry.node_count, geometry.bounds, geometry.planes, geometry.plane_count, lists.counts,
                                lists.offsets, lists.candidates);
  filled.wait();
  stats.culling_ms += event_milliseconds(counted) + event_milliseconds(filled);
  stats.pairs = pairs;
  stats.entries = total;
}

ShadowCullingStats ShadowCuller::cull(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                                      std::size_t slot_count, const TileLayout& layout,
                                      const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                                      std::size_t light_count, float offset_scale, float eye_extent) {
  ShadowCullingStats stats;
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t tiles = std::max<std::size_t>(layout.tile_count, 1);
  const cl::Buffer boxes(context, CL_MEM_READ_WRITE, tiles * sizeof(TileBox));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, TileGrid, cl::Buffer> bounds(bounds_program_, "tile_bounds");
  const cl::Event boxed = bounds(cl::EnqueueArgs(queue, cl::NDRange(layout.tile_count)), planes,
                                 static_cast<cl_uint>(plane_stride), material_index, static_cast<cl_uint>(slot_count),
                                 layout.grid, boxes);

  // The coarse level's boxes, merged from the tiles'.
  const cl_uint ratio = PHONGCL_SHADOW_COARSE_RATIO;
  const cl_uint rows = static_cast<cl_uint>(layout.tile_count / layout.grid.tiles_x);
  coarse_.grid = layout.grid;
  coarse_.grid.tile_size *= ratio;
  coarse_.grid.tiles_x = (layout.grid.tiles_x + ratio - 1) / ratio;
  coarse_.tiles = coarse_.grid.tiles_x * ((rows + ratio - 1) / ratio);
  const cl::Buffer coarse_boxes(context, CL_MEM_READ_WRITE, coarse_.tiles * sizeof(TileBox));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl_uint, cl_uint, cl_uint, cl::Buffer> merge(cull_program_, "merge_tile_boxes");
  const cl::Event merged = merge(cl::EnqueueArgs(queue, cl::NDRange(coarse_.tiles)), boxes, layout.grid.tiles_x,
                                 static_cast<cl_uint>(layout.tile_count), ratio, coarse_.grid.tiles_x, coarse_boxes);
  ShadowCullingStats coarse_stats;
  level(coarse_, coarse_boxes, PHONGCL_SHADOW_COARSE_LIMIT, CullLevel{}, nullptr, geometry, lights, light_count,
        offset_scale, eye_extent, coarse_stats);
  fine_.grid = layout.grid;
  fine_.tiles = static_cast<cl_uint>(layout.tile_count);
  level(fine_, boxes, PHONGCL_SHADOW_CANDIDATE_LIMIT, CullLevel{ratio, layout.grid.tiles_x, coarse_.grid.tiles_x, coarse_.tiles},
        &coarse_, geometry, lights, light_count, offset_scale, eye_extent, stats);
  stats.culling_ms += coarse_stats.culling_ms + event_milliseconds(boxed) + event_milliseconds(merged);
  return stats;
}

}  // namespace phongcl
