#pragma once
// Tiled shadow culling on the device (kernels/shadow_cull.cl): per screen tile and shadow-casting
// light, the primitives and planes that can block the tile's shadow rays toward it, in two levels
// (tiles of PHONGCL_SHADOW_COARSE_RATIO^2 tiles walk the BVH; each tile filters its parent's list).
// The shading kernel then tests a pixel's few candidates instead of traversing the BVH.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "cl/program_cache.h"
#include "shading/device_layout.h"
#include "shading/shadow_buffers.h"
#include "shading/tile_culling.h"

namespace phongcl {

// What the kernels read: pair p = light * tiles + tile has counts[p] candidates from
// candidates[offsets[p]], or counts[p] == PHONGCL_SHADOW_TRAVERSE (its rays traverse the BVH). The
// tiles' level keeps the three in one block (phong_shade's shadow_lists), `tables` saying where.
struct ShadowLists {
  cl::Buffer counts{}, offsets{}, candidates{};  // sub-buffers of `block` where there is one
  cl::Buffer block{};
  ShadowListTables tables{};
  TileGrid grid{};
  cl_uint tiles = 0;
  std::vector<cl_uint> host_counts{};  // the coarse level's, which size the tiles' room
};

class ShadowCuller {
 public:
  // `shading_options`: the shading variant's build options, whose lanes and storage cull.cl takes.
  ShadowCuller(const ComputeContext& compute, ProgramCache& cache, const std::string& shading_options);

  // Culls one launch's slots [0, slot_count) (packed as kernels/layout.h says) for `lights`
  // (ShadowLight, light_count of them). `packing` numbers what the slots hold (BoxesKey): the
  // tiles' boxes of shaded positions of the last cull serve the same one.
  ShadowCullingStats cull(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                          std::size_t slot_count, const TileLayout& layout, const ShadowGeometryBuffers& geometry,
                          const cl::Buffer& lights, std::size_t light_count, float offset_scale, float eye_extent,
                          std::uint64_t packing = 0);

  const ShadowLists& lists() const { return fine_; }

 private:
  // The coarse level from the BVH: counts, the host's prefix sum, then the lists.
  void coarse_level(const cl::Buffer& boxes, const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                    std::size_t light_count, float offset_scale, float eye_extent, ShadowCullingStats& stats);
  // The tiles' level in one pass, each pair given room for as many entries as its parent has.
  void fine_level(const cl::Buffer& boxes, const ShadowGeometryBuffers& geometry, const cl::Buffer& lights,
                  std::size_t light_count, float offset_scale, float eye_extent, ShadowCullingStats& stats);
  // The tiles' boxes (cull.cl's tile_bounds) and the coarse level's, merged from them; returns the
  // passes' milliseconds.
  double box_tiles(const cl::Buffer& planes, std::size_t plane_stride, const cl::Buffer& material_index,
                   std::size_t slot_count, const TileLayout& layout);

  ComputeContext compute_;
  cl::Program bounds_program_, cull_program_;
  ShadowLists coarse_, fine_;
  cl::Buffer boxes_, coarse_boxes_;
  std::optional<BoxesKey> boxes_for_;  // what boxes_ were taken for
};

}  // namespace phongcl
