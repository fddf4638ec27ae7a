#pragma once
// Tiled light culling on the device (kernels/cull.cl): per screen tile, the box of its shaded
// positions, then (boxes of 8 x 8, 4 x 4 and 2 x 2 tiles first) the list of point and spot lights whose
// bounds reach it; phong_shade's TILED_CULLING variant loops over its tile's list only.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cl/program_cache.h"
#include "cl/reusable_buffer.h"
#include "shading/device_layout.h"
#include "shading/shade_stats.h"  // CullingStats

namespace phongcl {

// The grid of tile_size x tile_rows tiles over an image of the given width and height.
struct TileLayout {
  TileGrid grid{};
  std::size_t tile_count = 0;
};
TileLayout tile_layout(int width, int height, int tile_size, int tile_rows);
// The tiles the shading's light lists are kept for: square tiles of an even size split into a top
// and a bottom half. A work-item shades tile_size pixels of one row, so a half's list serves
// tile_size / 2 rows of work-items, not tile_size, and holds fewer lights (the kernel tests each
// light that does not hold all of its tile against each row).
TileLayout light_list_layout(int width, int height, int tile_size);
// What a launch's tile boxes are taken from: its slots' packing, numbered by whoever packs them (a
// new number each time they are packed; 0: not numbered), and the tiles. The boxes depend on the
// pixels alone, so a cull of the same numbered packing and tiles (only the lights changed) keeps them.
struct BoxesKey {
  std::uint64_t packing = 0;
  TileLayout layout;
};
// Whether boxes taken for `taken` (none: never taken) serve `wanted`.
bool boxes_serve(const std::optional<BoxesKey>& taken, const BoxesKey& wanted);

// cull.cl's options for a shading variant's build options (its lanes and storage) and blocks of
// `block_boxes` boxes (4 or 8).
std::string culling_options(const std::string& shading_options, int block_boxes = 4);

// The boxes of a launch's tiles (layout.tile_count TileBoxes into `boxes`) from its packed slots
// [0, slot_count), by cull.cl's tile_bounds; returns its event.
cl::Event enqueue_tile_boxes(cl::CommandQueue& queue, const cl::Program& cull_program, const cl::Buffer& planes,
                             std::size_t plane_stride, const cl::Buffer& material_index, std::size_t slot_count,
                             const TileLayout& layout, const cl::Buffer& boxes);

struct BoxGrid;  // one culling level's boxes (tile_culling.cpp)

class TileCuller {
 public:
  // `build_options` carries the shading recipe's PHONGCL_LANES and HALF_STORAGE.
  TileCuller(const ComputeContext& compute, ProgramCache& cache, const std::string& build_options);

  // Culls one launch's slots [0, slot_count) (frame pixels grid.first_pixel onwards) against the
  // lights; afterwards block() holds the lists phong_shade reads. `packing`
  // numbers what the slots hold (BoxesKey): the tiles' boxes of the last cull serve the same one.
  CullingStats cull(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                    std::size_t slot_count, const TileLayout& layout, const cl::Buffer& light_bounds,
                    std::size_t light_count, std::uint64_t packing = 0);

  // The tiles' lists in one block (phong_shade's tile_lists) and where each table starts in it: tile t's
  // lights from lights[offsets[t]], counts[t] of them, led by the holding[t] whose bounds hold all of
  // the tile's box.
  const cl::Buffer& block() const { return block_; }
  const TileListTables& tables() const { return tables_; }

 private:
  // One level of culling: each block's candidates (a range of `candidates`: block b's from
  // candidate_first[b], candidate_count[b] of them, the first candidate_holding[b] holding all of the
  // block's boxes) against its boxes (`boxes` on the device, grid.boxes the same on the host); box t's
  // list is lights[host_offsets[t] ...], host_counts[t] of them, led by the host_holding[t] whose
  // bounds hold all of the box.
  struct Lists {
    cl::Buffer block;        // the tables below, in one buffer
    TileListTables tables{};  // where each starts in it
    cl::Buffer offsets, counts, lights, holding;  // each table as a sub-buffer, for cull.cl
    std::vector<cl_uint> host_offsets, host_counts, host_holding;
  };
  // A level's device lists, kept from frame to frame: fresh ones cost page faults every frame (at
  // 10,000 lights the coarsest level has room for 1.35 million entries; kept, the frame took 0.98 of
  // its time).
  struct LevelBuffers {
    ReusableBuffer block{CL_MEM_READ_WRITE};
  };
  Lists lists(const cl::Buffer& boxes, const BoxGrid& grid, const cl::Buffer& light_bounds,
              const cl::Buffer& candidates, const std::vector<cl_uint>& candidate_first,
              const std::vector<cl_uint>& candidate_count, const std::vector<cl_uint>& candidate_holding,
              bool sieve, LevelBuffers& buffers);

  ComputeContext compute_;
  cl::Program program_, halves_program_;  // blocks of 2 x 2 boxes, of 2 x 4 half tiles
  ReusableBuffer boxes_{CL_MEM_READ_WRITE};
  std::vector<TileBox> tile_boxes_;      // boxes_ read back
  std::optional<BoxesKey> boxes_for_;    // what they were taken for
  std::vector<LevelBuffers> level_buffers_;  // the tiles' first
  cl::Buffer block_;
  TileListTables tables_{};
};

}  // namespace phongcl
