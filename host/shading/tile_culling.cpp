#include "shading/tile_culling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "cl/kernel_source.h"
#include "cl/table_block.h"
#include "cl/work_groups.h"

namespace phongcl {

namespace {

using KeepKernel = cl::KernelFunctor<cl::Buffer, cl::Buffer, cl::Buffer, cl::Buffer, cl::Buffer, cl::Buffer, cl::Buffer,
                                    cl::Buffer, cl::Buffer, cl::Buffer, cl::Buffer, cl_uint>;

}  // namespace

// The lane count and storage type are all cull.cl shares with the shading variant.
std::string culling_options(const std::string& shading_options, int block_boxes) {
  std::string options = "-cl-std=CL1.2 -DPHONGCL_BLOCK_BOXES=" + std::to_string(block_boxes);
  for (const char* keep : {"-DPHONGCL_LANES=", "-DHALF_STORAGE"}) {
    const std::size_t at = shading_options.find(keep);
    if (at == std::string::npos) continue;
    options.append(" ").append(shading_options, at, shading_options.find(' ', at) - at);
  }
  return options;
}

cl::Event enqueue_tile_boxes(cl::CommandQueue& queue, const cl::Program& cull_program, const cl::Buffer& planes,
                             std::size_t plane_stride, const cl::Buffer& material_index, std::size_t slot_count,
                             const TileLayout& layout, const cl::Buffer& boxes) {
  using BoundsKernel = cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, TileGrid, cl::Buffer>;
  BoundsKernel by_tile(cull_program, "tile_bounds");
  return by_tile(cl::EnqueueArgs(queue, cl::NDRange(layout.tile_count)), planes, static_cast<cl_uint>(plane_stride),
                 material_index, static_cast<cl_uint>(slot_count), layout.grid, boxes);
}

CullingStats& CullingStats::operator+=(const CullingStats& other) {
  tile_size = other.tile_size;
  tile_rows = other.tile_rows;
  tiles = std::max(tiles, other.tiles);
  shaded_tiles += other.shaded_tiles;
  max_lights_per_tile = std::max(max_lights_per_tile, other.max_lights_per_tile);
  list_entries += other.list_entries;
  holding_entries += other.holding_entries;
  kept_pairs += other.kept_pairs;
  culling_ms += other.culling_ms;
  return *this;
}

TileLayout tile_layout(int width, int height, int tile_size, int tile_rows) {
  TileLayout layout;
  const auto size = static_cast<cl_uint>(tile_size), rows = static_cast<cl_uint>(tile_rows);
  layout.grid.image_width = static_cast<cl_uint>(width);
  layout.grid.tile_size = size;
  layout.grid.tile_rows = rows;
  layout.grid.tiles_x = (static_cast<cl_uint>(width) + size - 1) / size;
  layout.tile_count =
      static_cast<std::size_t>(layout.grid.tiles_x) * ((static_cast<cl_uint>(height) + rows - 1) / rows);
  return layout;
}

TileLayout light_list_layout(int width, int height, int tile_size) {
  return tile_layout(width, height, tile_size, tile_size % 2 == 0 ? tile_size / 2 : tile_size);
}

bool boxes_serve(const std::optional<BoxesKey>& taken, const BoxesKey& wanted) {
  return taken && wanted.packing != 0 && taken->packing == wanted.packing &&
         taken->layout.tile_count == wanted.layout.tile_count &&
         std::memcmp(&taken->layout.grid, &wanted.layout.grid, sizeof(TileGrid)) == 0;
}

TileCuller::TileCuller(const ComputeContext& compute, ProgramCache& cache, const std::string& build_options)
    : compute_(compute),
      program_(cache.build(compute, load_kernel_source("cull.cl"), culling_options(build_options, 4)).program),
      halves_program_(cache.build(compute, load_kernel_source("cull.cl"), culling_options(build_options, 8)).program) {}

// The culling levels above the square tiles are boxes of 2 x 2, 4 x 4 and 8 x 8 of them: every light
// is tested against the coarsest boxes, and each finer box against its parent's survivors.
constexpr std::size_t kCoarsestSpan = 8;

// A grid of boxes, each the union of the tile boxes it spans, and its blocks of 2 x block_rows boxes
// (2 x 4 half tiles, or 2 x 2 boxes): blocks[b * block_size() ...] holds the indices of the boxes the
// parent box b (one level up) is made of, PHONGCL_NO_BOX where the grid ends.
struct BoxGrid {
  std::size_t columns = 0;
  std::vector<TileBox> boxes{};
  std::size_t block_rows = 2;
  std::vector<cl_uint> blocks{};
  std::size_t block_size() const { return 2 * block_rows; }
};

namespace {

// The boxes of `grid` merged 2 x block_rows (and grid.blocks filled: the merged box m is made of
// block m).
BoxGrid merge_blocks(BoxGrid& grid, std::size_t block_rows = 2) {
  grid.block_rows = block_rows;
  const std::size_t rows = grid.boxes.size() / grid.columns;
  BoxGrid merged;
  merged.columns = (grid.columns + 1) / 2;
  merged.boxes.resize(merged.columns * ((rows + block_rows - 1) / block_rows));
  for (TileBox& box : merged.boxes) {
    for (int axis = 0; axis < 3; ++axis) box.lo[axis] = INFINITY, box.hi[axis] = -INFINITY;
    box.shaded = box.distance_bins = 0;
  }
  grid.blocks.assign(merged.boxes.size() * grid.block_size(), PHONGCL_NO_BOX);
  for (std::size_t t = 0; t < grid.boxes.size(); ++t) {
    const std::size_t column = t % grid.columns, row = t / grid.columns;
    const std::size_t m = row / block_rows * merged.columns + column / 2;
    grid.blocks[m * grid.block_size() + row % block_rows * 2 + column % 2] = static_cast<cl_uint>(t);
    const TileBox& box = grid.boxes[t];
    if (box.shaded == 0) continue;
    for (int axis = 0; axis < 3; ++axis) {
      merged.boxes[m].lo[axis] = std::min(merged.boxes[m].lo[axis], box.lo[axis]);
      merged.boxes[m].hi[axis] = std::max(merged.boxes[m].hi[axis], box.hi[axis]);
    }
    merged.boxes[m].shaded += box.shaded;
    merged.boxes[m].distance_bins |= box.distance_bins;
  }
  return merged;
}

template <typename T>
cl::Buffer device_copy(const cl::Context& context, std::vector<T> values) {
  if (values.empty()) values.resize(1);
  return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * sizeof(T), values.data());
}

}  // namespace

TileCuller::Lists TileCuller::lists(const cl::Buffer& boxes, const BoxGrid& grid, const cl::Buffer& light_bounds,
                                    const cl::Buffer& candidates, const std::vector<cl_uint>& candidate_first,
                                    const std::vector<cl_uint>& candidate_count,
                                    const std::vector<cl_uint>& candidate_holding, bool sieve,
                                    LevelBuffers& buffers) {
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t box_count = grid.boxes.size();
  Lists lists;
  // Room for every candidate of each shaded box, so that one pass both tests and writes.
  lists.host_offsets.assign(box_count, 0);
  std::size_t room = 0;
  for (std::size_t b = 0; b < candidate_count.size(); ++b)
    for (std::size_t slot = 0; slot < grid.block_size(); ++slot) {
      const cl_uint t = grid.blocks[b * grid.block_size() + slot];
      if (t == PHONGCL_NO_BOX) continue;
      lists.host_offsets[t] = static_cast<cl_uint>(room);
      if (grid.boxes[t].shaded > 0) room += candidate_count[b];
    }
  if (room > std::numeric_limits<cl_uint>::max())
    throw std::runtime_error("tiled culling: the light lists need over 2^32 entries (lights without a range are in "
                             "every tile's list): use a larger --tile or --culling none");
  // One block, kept from frame to frame; OpenCL has no empty buffers: a frame that keeps no light
  // still gets one entry.
  TableBlockLayout layout(sub_buffer_alignment(context));
  lists.tables = {.offsets = layout.add(lists.host_offsets),
                  .counts = layout.reserve(box_count * sizeof(cl_uint)),
                  .holding = layout.reserve(box_count * sizeof(cl_uint)),
                  .lights = layout.reserve(room * sizeof(cl_uint))};
  lists.block = buffers.block.at_least(context, layout.bytes());
  layout.write(queue, lists.block);
  lists.offsets = layout.table(lists.block, lists.tables.offsets);
  lists.counts = layout.table(lists.block, lists.tables.counts);
  lists.holding = layout.table(lists.block, lists.tables.holding);
  lists.lights = layout.table(lists.block, lists.tables.lights);
  // One block per group: PoCL's default put each level's blocks (2,040 at the tiles of a 1080p frame)
  // in one group, on one core; at 10,000 lights the four levels took 6.1 against 9.5 ms.
  const std::size_t blocks = candidate_count.size();
  KeepKernel(grid.block_rows == 2 ? program_ : halves_program_, "keep_box_lights")(
      cl::EnqueueArgs(queue, cl::NDRange(blocks), spread_work_groups(compute_.device.info, blocks, 1)), boxes,
      light_bounds, device_copy(context, grid.blocks), candidates, device_copy(context, candidate_first),
      device_copy(context, candidate_count), device_copy(context, candidate_holding), lists.offsets, lists.lights,
      lists.counts, lists.holding, cl_uint{sieve});
  lists.host_counts.resize(box_count);
  lists.host_holding.resize(box_count);
  queue.enqueueReadBuffer(lists.counts, CL_FALSE, 0, box_count * sizeof(cl_uint), lists.host_counts.data());
  queue.enqueueReadBuffer(lists.holding, CL_TRUE, 0, box_count * sizeof(cl_uint), lists.host_holding.data());
  return lists;
}

CullingStats TileCuller::cull(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                              std::size_t slot_count, const TileLayout& layout, const cl::Buffer& light_bounds,
                              std::size_t light_count, std::uint64_t packing) {
  const auto start = std::chrono::steady_clock::now();
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  const std::size_t tiles = layout.tile_count;
  const cl::Buffer& boxes = boxes_.at_least(context, tiles * sizeof(TileBox));
  const BoxesKey wanted{packing, layout};
  if (!boxes_serve(boxes_for_, wanted)) {
    boxes_for_.reset();
    enqueue_tile_boxes(queue, program_, planes, plane_stride, material_index, slot_count, layout, boxes);
    tile_boxes_.resize(tiles);
    queue.enqueueReadBuffer(boxes, CL_TRUE, 0, tiles * sizeof(TileBox), tile_boxes_.data());
    boxes_for_ = wanted;
  }

  // The levels' box grids, finest (the tiles) first, each with its blocks; the coarsest's blocks are
  // the boxes of a grid not culled against. Tiles half as tall as wide make boxes of 2 x 2 squares
  // in blocks of 2 x 4.
  std::vector<BoxGrid> grids{{layout.grid.tiles_x, tile_boxes_, {}}};
  const bool halves = layout.grid.tile_rows < layout.grid.tile_size;
  if (halves) grids.push_back(merge_blocks(grids.back(), 4));
  for (std::size_t span = halves ? 2 : 1; span < kCoarsestSpan; span *= 2) grids.push_back(merge_blocks(grids.back()));
  merge_blocks(grids.back());
  // The coarsest level tests every light; each finer box its parent box's survivors.
  std::vector<cl_uint> every_light(light_count);
  for (std::size_t k = 0; k < light_count; ++k) every_light[k] = static_cast<cl_uint>(k);
  const std::size_t coarsest_blocks = grids.back().blocks.size() / grids.back().block_size();
  level_buffers_.resize(grids.size());
  Lists level = lists(device_copy(context, grids.back().boxes), grids.back(), light_bounds,
                      device_copy(context, every_light), std::vector<cl_uint>(coarsest_blocks, 0),
                      std::vector<cl_uint>(coarsest_blocks, static_cast<cl_uint>(light_count)),
                      std::vector<cl_uint>(coarsest_blocks, 0), true, level_buffers_.back());
  for (std::size_t g = grids.size() - 1; g-- > 0;) {
    const cl::Buffer finer = g == 0 ? boxes : device_copy(context, grids[g].boxes);
    level = lists(finer, grids[g], light_bounds, level.lights, level.host_offsets, level.host_counts,
                  level.host_holding, false, level_buffers_[g]);
  }
  const Lists& fine = level;
  block_ = fine.block;
  tables_ = fine.tables;

  CullingStats stats;
  stats.tile_size = static_cast<int>(layout.grid.tile_size);
  stats.tile_rows = static_cast<int>(layout.grid.tile_rows);
  stats.tiles = tiles;
  const std::vector<TileBox>& tile_boxes = grids.front().boxes;
  for (std::size_t t = 0; t < tiles; ++t) {
    if (tile_boxes[t].shaded == 0) continue;
    ++stats.shaded_tiles;
    stats.max_lights_per_tile = std::max<std::size_t>(stats.max_lights_per_tile, fine.host_counts[t]);
    stats.list_entries += fine.host_counts[t];
    stats.holding_entries += fine.host_holding[t];
    stats.kept_pairs += static_cast<double>(fine.host_counts[t]) * tile_boxes[t].shaded;
  }
  stats.culling_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phongcl
