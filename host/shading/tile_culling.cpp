#include "shading/tile_culling.h"

#include <algorithm>
#include <chrono>

#include "cl/kernel_source.h"

namespace phongcl {

namespace {

using BoundsKernel = cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, TileGrid, cl::Buffer>;
using CountKernel = cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint, cl::Buffer>;
using FillKernel = cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer>;

// The lane count and storage type are all cull.cl shares with the shading variant.
std::string culling_options(const std::string& shading_options) {
  std::string options = "-cl-std=CL1.2";
  for (const char* keep : {"-DPHONGCL_LANES=", "-DHALF_STORAGE"}) {
    const std::size_t at = shading_options.find(keep);
    if (at == std::string::npos) continue;
    options += " " + shading_options.substr(at, shading_options.find(' ', at) - at);
  }
  return options;
}

}  // namespace

CullingStats& CullingStats::operator+=(const CullingStats& other) {
  tile_size = other.tile_size;
  tiles = std::max(tiles, other.tiles);
  shaded_tiles += other.shaded_tiles;
  max_lights_per_tile = std::max(max_lights_per_tile, other.max_lights_per_tile);
  list_entries += other.list_entries;
  kept_pairs += other.kept_pairs;
  culling_ms += other.culling_ms;
  return *this;
}

TileLayout tile_layout(int width, int height, int tile_size) {
  TileLayout layout;
  const auto size = static_cast<cl_uint>(tile_size);
  layout.grid.image_width = static_cast<cl_uint>(width);
  layout.grid.tile_size = size;
  layout.grid.tiles_x = (static_cast<cl_uint>(width) + size - 1) / size;
  layout.tile_count = static_cast<std::size_t>(layout.grid.tiles_x) * ((static_cast<cl_uint>(height) + size - 1) / size);
  return layout;
}

TileCuller::TileCuller(const ComputeContext& compute, ProgramCache& cache, const std::string& build_options)
    : compute_(compute), program_(cache.build(compute, load_kernel_source("cull.cl"), culling_options(build_options)).program) {}

CullingStats TileCuller::cull(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                              std::size_t slot_count, const TileLayout& layout, const cl::Buffer& light_bounds,
                              std::size_t light_count) {
  const auto start = std::chrono::steady_clock::now();
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t tiles = layout.tile_count;
  const cl::Buffer& boxes = boxes_.at_least(context, tiles * sizeof(TileBox));
  counts_buffer_ = counts_.at_least(context, tiles * sizeof(cl_uint));
  offsets_buffer_ = offsets_.at_least(context, tiles * sizeof(cl_uint));
  BoundsKernel(program_, "tile_bounds")(cl::EnqueueArgs(queue, cl::NDRange(tiles)), planes,
                                        static_cast<cl_uint>(plane_stride), material_index,
                                        static_cast<cl_uint>(slot_count), layout.grid, boxes);
  CountKernel(program_, "count_tile_lights")(cl::EnqueueArgs(queue, cl::NDRange(tiles)), boxes, light_bounds,
                                             static_cast<cl_uint>(light_count), counts_buffer_);

  // Offsets: an exclusive prefix sum of the counts, on the host (a few thousand values).
  std::vector<TileBox> box_values(tiles);
  queue.enqueueReadBuffer(boxes, CL_TRUE, 0, tiles * sizeof(TileBox), box_values.data());
  const auto* counts = static_cast<const cl_uint*>(
      queue.enqueueMapBuffer(counts_buffer_, CL_TRUE, CL_MAP_READ, 0, tiles * sizeof(cl_uint)));
  auto* offsets = static_cast<cl_uint*>(
      queue.enqueueMapBuffer(offsets_buffer_, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, tiles * sizeof(cl_uint)));
  CullingStats stats;
  stats.tile_size = static_cast<int>(layout.grid.tile_size);
  stats.tiles = tiles;
  std::size_t total = 0;
  for (std::size_t t = 0; t < tiles; ++t) {
    offsets[t] = static_cast<cl_uint>(total);
    total += counts[t];
    if (box_values[t].shaded == 0) continue;
    ++stats.shaded_tiles;
    stats.max_lights_per_tile = std::max<std::size_t>(stats.max_lights_per_tile, counts[t]);
    stats.list_entries += counts[t];
    stats.kept_pairs += static_cast<double>(counts[t]) * box_values[t].shaded;
  }
  queue.enqueueUnmapMemObject(counts_buffer_, const_cast<cl_uint*>(counts));
  queue.enqueueUnmapMemObject(offsets_buffer_, offsets);

  // OpenCL has no empty buffers: a frame that keeps no light still gets one entry.
  lights_buffer_ = lights_.at_least(context, std::max<std::size_t>(total, 1) * sizeof(cl_uint));
  FillKernel(program_, "fill_tile_lights")(cl::EnqueueArgs(queue, cl::NDRange(tiles)), boxes, light_bounds,
                                           static_cast<cl_uint>(light_count), offsets_buffer_, lights_buffer_);
  queue.finish();
  stats.culling_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phongcl
