#include "shading/shadow_culling.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "cl/kernel_source.h"
#include "cl/table_block.h"

namespace phongcl {

ShadowCullingStats& ShadowCullingStats::operator+=(const ShadowCullingStats& other) {
  culling_ms += other.culling_ms;
  pairs += other.pairs;
  entries += other.entries;
  traversing += other.traversing;
  return *this;
}

ShadowCuller::ShadowCuller(const ComputeContext& compute, ProgramCache& cache, const std::string& shading_options)
    : compute_(compute),
      bounds_program_(cache.build(compute, load_kernel_source("cull.cl"), culling_options(shading_options)).program),
      // phong_math.h as one lane of float.
      cull_program_(cache.build(compute, load_kernel_source("shadow_cull.cl"),
                                "-cl-std=CL1.2 -DPHONGCL_LANES=1 -DPHONGCL_DOUBLE=0 -DPHONGCL_FAST=0").program) {}

namespace {

double since_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void ShadowCuller::coarse_level(const cl::Buffer& boxes, const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                                std::size_t light_count, float offset_scale, float eye_extent, ShadowCullingStats& stats) {
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t pairs = static_cast<std::size_t>(coarse_.tiles) * light_count;
  const cl::Buffer none(context, CL_MEM_READ_ONLY, sizeof(ShadowCandidate));
  coarse_.counts = cl::Buffer(context, CL_MEM_READ_WRITE, std::max<std::size_t>(pairs, 1) * sizeof(cl_uint));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_float, cl_float, cl_uint, CullLevel, cl::Buffer, cl::Buffer, cl::Buffer,
                    cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer>
      count(cull_program_, "count_shadow_candidates");
  const cl::Event counted = count(cl::EnqueueArgs(queue, cl::NDRange(pairs)), boxes, coarse_.tiles, lights, offset_scale,
                                  eye_extent, PHONGCL_SHADOW_COARSE_LIMIT, CullLevel{}, none, none, none, geometry.nodes,
                                  geometry.node_count, geometry.bounds, geometry.planes, geometry.plane_count, coarse_.counts);
  coarse_.host_counts.resize(pairs);
  queue.enqueueReadBuffer(coarse_.counts, CL_TRUE, 0, pairs * sizeof(cl_uint), coarse_.host_counts.data());
  // Offsets: an exclusive prefix sum of the counts, on the host; pairs beyond the limit take none.
  const auto prefix_start = std::chrono::steady_clock::now();
  std::vector<cl_uint> offsets(pairs);
  std::size_t total = 0;
  for (std::size_t p = 0; p < pairs; ++p) {
    offsets[p] = static_cast<cl_uint>(total);
    if (coarse_.host_counts[p] != PHONGCL_SHADOW_TRAVERSE) total += coarse_.host_counts[p];
  }
  coarse_.offsets = table_buffer(context, offsets);
  stats.culling_ms += since_ms(prefix_start);
  coarse_.candidates = cl::Buffer(context, CL_MEM_READ_WRITE, std::max<std::size_t>(total, 1) * sizeof(ShadowCandidate));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_float, cl_float, CullLevel, cl::Buffer, cl::Buffer, cl::Buffer,
                    cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl::Buffer>
      fill(cull_program_, "fill_shadow_candidates");
  const cl::Event filled = fill(cl::EnqueueArgs(queue, cl::NDRange(pairs)), boxes, coarse_.tiles, lights, offset_scale,
                                eye_extent, CullLevel{}, none, none, none, geometry.nodes, geometry.node_count,
                                geometry.bounds, geometry.planes, geometry.plane_count, coarse_.counts, coarse_.offsets,
                                coarse_.candidates);
  filled.wait();
  stats.culling_ms += event_milliseconds(counted) + event_milliseconds(filled);
}

void ShadowCuller::fine_level(const cl::Buffer& boxes, const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                              std::size_t light_count, float offset_scale, float eye_extent, ShadowCullingStats& stats) {
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const cl_uint ratio = PHONGCL_SHADOW_COARSE_RATIO, limit = PHONGCL_SHADOW_CANDIDATE_LIMIT;
  const CullLevel level{ratio, fine_.grid.tiles_x, coarse_.grid.tiles_x, coarse_.tiles};
  const std::size_t pairs = static_cast<std::size_t>(fine_.tiles) * light_count;
  // Room: a tile's list is part of its parent's (up to the limit; a parent that traverses, the limit).
  const auto prefix_start = std::chrono::steady_clock::now();
  std::vector<cl_uint> offsets(pairs);
  std::size_t room = 0;
  for (std::size_t p = 0; p < pairs; ++p) {
    const std::size_t tile = p % fine_.tiles, light = p / fine_.tiles;
    const std::size_t parent = (tile / level.tiles_x / ratio) * level.parent_tiles_x + tile % level.tiles_x / ratio;
    const cl_uint parent_count = coarse_.host_counts[light * coarse_.tiles + parent];
    offsets[p] = static_cast<cl_uint>(room);
    room += parent_count == PHONGCL_SHADOW_TRAVERSE ? limit : std::min(parent_count, limit);
  }
  TableBlockLayout layout(sub_buffer_alignment(context));
  fine_.tables = {.counts = layout.reserve(pairs * sizeof(cl_uint)),
                  .offsets = layout.add(offsets),
                  .candidates = layout.reserve(room * sizeof(ShadowCandidate))};
  fine_.block = layout.upload(context, CL_MEM_READ_WRITE);
  stats.culling_ms += since_ms(prefix_start);
  fine_.counts = layout.table(fine_.block, fine_.tables.counts);
  fine_.offsets = layout.table(fine_.block, fine_.tables.offsets);
  fine_.candidates = layout.table(fine_.block, fine_.tables.candidates);
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_float, cl_float, cl_uint, CullLevel, cl::Buffer, cl::Buffer, cl::Buffer,
                    cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl::Buffer>
      collect(cull_program_, "collect_shadow_candidates");
  const cl::Event collected = collect(cl::EnqueueArgs(queue, cl::NDRange(pairs)), boxes, fine_.tiles, lights, offset_scale,
                                      eye_extent, limit, level, coarse_.counts, coarse_.offsets, coarse_.candidates,
                                      geometry.nodes, geometry.node_count, geometry.bounds, geometry.planes,
                                      geometry.plane_count, fine_.offsets, fine_.counts, fine_.candidates);
  fine_.host_counts.resize(pairs);
  queue.enqueueReadBuffer(fine_.counts, CL_TRUE, 0, pairs * sizeof(cl_uint), fine_.host_counts.data());
  stats.culling_ms += event_milliseconds(collected);
  stats.pairs = pairs;
  for (cl_uint count : fine_.host_counts) {
    if (count == PHONGCL_SHADOW_TRAVERSE) ++stats.traversing;
    else stats.entries += count;
  }
}

ShadowCullingStats ShadowCuller::cull(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                                      std::size_t slot_count, const TileLayout& layout,
                                      const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                                      std::size_t light_count, float offset_scale, float eye_extent,
                                      std::uint64_t packing) {
  ShadowCullingStats stats;
  const BoxesKey wanted{packing, layout};
  if (!boxes_serve(boxes_for_, wanted)) {
    boxes_for_.reset();
    stats.culling_ms += box_tiles(planes, plane_stride, material_index, slot_count, layout);
    boxes_for_ = wanted;
  }
  coarse_level(coarse_boxes_, geometry, lights, light_count, offset_scale, eye_extent, stats);
  fine_.grid = layout.grid;
  fine_.tiles = static_cast<cl_uint>(layout.tile_count);
  fine_level(boxes_, geometry, lights, light_count, offset_scale, eye_extent, stats);
  return stats;
}

double ShadowCuller::box_tiles(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                               std::size_t slot_count, const TileLayout& layout) {
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t tiles = std::max<std::size_t>(layout.tile_count, 1);
  boxes_ = cl::Buffer(context, CL_MEM_READ_WRITE, tiles * sizeof(TileBox));
  const cl::Event boxed =
      enqueue_tile_boxes(queue, bounds_program_, planes, plane_stride, material_index, slot_count, layout, boxes_);

  // The coarse level's boxes, merged from the tiles'.
  const cl_uint ratio = PHONGCL_SHADOW_COARSE_RATIO;
  const cl_uint rows = static_cast<cl_uint>(layout.tile_count / layout.grid.tiles_x);
  coarse_.grid = layout.grid;
  coarse_.grid.tile_size *= ratio;
  coarse_.grid.tile_rows *= ratio;
  coarse_.grid.tiles_x = (layout.grid.tiles_x + ratio - 1) / ratio;
  coarse_.tiles = coarse_.grid.tiles_x * ((rows + ratio - 1) / ratio);
  coarse_boxes_ = cl::Buffer(context, CL_MEM_READ_WRITE, coarse_.tiles * sizeof(TileBox));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl_uint, cl_uint, cl_uint, cl::Buffer> merge(cull_program_, "merge_tile_boxes");
  const cl::Event merged = merge(cl::EnqueueArgs(queue, cl::NDRange(coarse_.tiles)), boxes_, layout.grid.tiles_x,
                                 static_cast<cl_uint>(layout.tile_count), ratio, coarse_.grid.tiles_x, coarse_boxes_);
  merged.wait();  // the in-order queue ran `boxed` first
  return event_milliseconds(boxed) + event_milliseconds(merged);
}

}  // namespace phongcl
