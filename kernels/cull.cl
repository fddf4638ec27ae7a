/* Tiled light culling (Andersson 2009; ISPC's examples/cpu/deferred), before phong_shade:
 *   row_bounds, tile_bounds  the box of each tile's shaded positions, in lane vectors (band by band)
 *   keep_box_lights    one work-item per 2 x 2 block of boxes: its candidate lights that can reach
 *                      each box, in order
 * The host runs the last once per level: boxes of 8 x 8 tiles with every light a candidate, then
 * boxes of 4 x 4 and 2 x 2 tiles and then the tiles, each with its parent box's list (the parent
 * being the box one level up that the block makes; shading/tile_culling.cpp). Each box writes its
 * list where the host left room for all of its candidates, so every light is tested once per level
 * and no list is compacted: the shading reads the tiles' lists where they are. A
 * light reaches a box when its bounding sphere (LightBounds, widened on the host against rounding)
 * meets it, or when it has no range, and for a spot when its cone can too, and when it spans one of
 * the distance bins of the box's positions (layout.h). The tile of a work-item
 * is the tile of its first pixel (tiles.h), so a tile's box covers every pixel its work-items shade.
 * Options: PHONGCL_LANES and HALF_STORAGE, as phong_shade's. */
/* The boxes are plain float whatever the shading's arithmetic. */
#define PHONGCL_DOUBLE 0
#define PHONGCL_FAST 0

#include "layout.h"
#include "phong_math.h"
#include "storage.h"
#include "tiles.h"

uint round_up_lanes(uint pixel) { return (pixel + PHONGCL_LANES - 1) / PHONGCL_LANES * PHONGCL_LANES; }

/* for REDUCE_LANES (phong_math.h) */
#define PLUS(a, b) ((a) + (b))
#define BIT_OR(a, b) ((a) | (b))

/* A tile's boxes are taken in two passes, so that the planes are read front to back: row_bounds,
 * one work-item per band of rows_per_item pixel rows of each tile (item = band * tiles_x + tile
 * column: a band's work-items are consecutive), then tile_bounds merges each tile's bands. One
 * work-item per tile read 32 strided rows of 128 bytes per plane, and took 10 ms for a 1080p frame
 * on 2 cores; one per row spent most of its time reducing its lanes (rows_per_item divides the tile
 * size: 4 where it can). */

/* The box of the shaded positions the work-items whose first pixel is in [row + x_begin,
 * row + x_end) shade, for each row of the band; those slots begin and end at multiples of
 * PHONGCL_LANES (so does first_pixel), so the box is taken over whole lane vectors, background lanes
 * left out by selects, and the lanes reduced once per band. */
__kernel void row_bounds(__global const STORAGE* restrict planes, uint plane_stride,
                         __global const int* restrict material_index, uint slot_count, TileGrid grid,
                         uint rows_per_item, __global TileBox* restrict rows) {
  const uint item = get_global_id(0);
  const uint tile_x = item % grid.tiles_x, band = item / grid.tiles_x;
  const uint x_begin = tile_x * grid.tile_size, x_end = min(x_begin + grid.tile_size, grid.image_width);
  floatv lo[3] = {(floatv)INFINITY, (floatv)INFINITY, (floatv)INFINITY};
  floatv hi[3] = {(floatv)-INFINITY, (floatv)-INFINITY, (floatv)-INFINITY};
  intv shaded = (intv)0, distance_bins = (intv)0;
  for (uint y = band * rows_per_item; y < (band + 1) * rows_per_item; ++y) {
    const ulong row = (ulong)y * grid.image_width;
    const ulong begin = max((ulong)round_up_lanes(row + x_begin), (ulong)grid.first_pixel);
    const ulong end = min((ulong)round_up_lanes(row + x_end), (ulong)grid.first_pixel + slot_count);
    for (ulong pixel = begin; pixel < end; pixel += PHONGCL_LANES) {
      const uint chunk = (uint)((pixel - grid.first_pixel) / PHONGCL_LANES);
      const intv is_shaded = VLOAD(chunk, material_index) != PHONGCL_BACKGROUND;
      const intv one_if_shaded = select((intv)0, (intv)1, is_shaded);
      shaded += one_if_shaded;
      floatv distance_sq = (floatv)0;
      for (int axis = 0; axis < 3; ++axis) {
        const floatv value = load_plane(planes, plane_stride, PLANE_PX + axis, chunk);
        lo[axis] = fmin(lo[axis], select((floatv)INFINITY, value, is_shaded));
        hi[axis] = fmax(hi[axis], select((floatv)-INFINITY, value, is_shaded));
        distance_sq += value * value;
      }
      const intv bin = (AS_INTV(distance_sq) >> PHONGCL_DISTANCE_BIN_SHIFT) & 31;
      distance_bins |= AS_INTV(AS_UINTV(one_if_shaded) << AS_UINTV(bin)); /* unsigned: bit 31 is no overflow */
    }
  }
  TileBox box;
  for (int axis = 0; axis < 3; ++axis) {
    box.lo[axis] = REDUCE_LANES(lo[axis], fmin);
    box.hi[axis] = REDUCE_LANES(hi[axis], fmax);
  }
  box.shaded = (uint)REDUCE_LANES(shaded, PLUS);
  box.distance_bins = (uint)REDUCE_LANES(distance_bins, BIT_OR);
  rows[item] = box;
}

/* A tile's box, the union of its bands' (row_bounds: tile_size / rows_per_item bands per tile). */
__kernel void tile_bounds(__global const TileBox* restrict rows, TileGrid grid, uint rows_per_item,
                          __global TileBox* restrict boxes) {
  const uint tile = get_global_id(0);
  const uint tile_x = tile % grid.tiles_x, tile_y = tile / grid.tiles_x, bands = grid.tile_size / rows_per_item;
  TileBox box = empty_tile_box();
  for (uint band = tile_y * bands; band < (tile_y + 1) * bands; ++band)
    add_to_box(&box, rows[band * grid.tiles_x + tile_x]);
  boxes[tile] = box;
}

/* Four boxes side by side, tested together against one light: a 2 x 2 block of one level's grid
 * (tile_culling.cpp), so that each candidate light is read once per block and tested in float4s. A
 * slot with no box holds an empty one (nothing shaded: it keeps nothing). */
typedef struct {
  float4 lo[3], hi[3];
  uint4 distance_bins;
  int4 shaded; /* -1 where the box has a shaded pixel, 0 elsewhere */
} BoxBlock;

BoxBlock box_block(__global const TileBox* boxes, const uint slots[4]) {
  TileBox box[4];
  for (int s = 0; s < 4; ++s) box[s] = slots[s] == PHONGCL_NO_BOX ? empty_tile_box() : boxes[slots[s]];
  BoxBlock block;
  for (int axis = 0; axis < 3; ++axis) {
    block.lo[axis] = (float4)(box[0].lo[axis], box[1].lo[axis], box[2].lo[axis], box[3].lo[axis]);
    block.hi[axis] = (float4)(box[0].hi[axis], box[1].hi[axis], box[2].hi[axis], box[3].hi[axis]);
  }
  block.distance_bins = (uint4)(box[0].distance_bins, box[1].distance_bins, box[2].distance_bins, box[3].distance_bins);
  block.shaded = (uint4)(box[0].shaded, box[1].shaded, box[2].shaded, box[3].shaded) > 0;
  return block;
}

int any_box(int4 mask) { return (mask.s0 | mask.s1 | mask.s2 | mask.s3) != 0; }

/* Where a light's bounding sphere meets the boxes: the squared distance from its centre to each box
 * against its radius squared. */
int4 sphere_meets_boxes(LightBounds light, const BoxBlock* block) {
  float4 distance_sq = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const float4 outside =
        fmax(fmax(block->lo[axis] - light.center[axis], light.center[axis] - block->hi[axis]), 0.0f);
    distance_sq += outside * outside;
  }
  return distance_sq <= light.radius * light.radius;
}

/* Where a spot's cone can meet the boxes. The cone (narrower than a hemisphere) lies behind the
 * plane through its apex across its axis, and behind the plane through its apex that touches it
 * along the side facing a box's centre; a box is out when all of it is in front of either. The slack
 * covers the rounding of the eye-relative floats. */
int4 cone_meets_boxes(LightBounds light, const BoxBlock* block) {
  float4 half_side[3], to_center[3], along = 0, length_sq = 0, size = 0;
  float apex_sq = 0;
  for (int axis = 0; axis < 3; ++axis) {
    half_side[axis] = 0.5f * (block->hi[axis] - block->lo[axis]);
    to_center[axis] = block->lo[axis] + half_side[axis] - light.apex[axis];
    along += to_center[axis] * light.axis[axis];
    length_sq += to_center[axis] * to_center[axis];
    apex_sq += light.apex[axis] * light.apex[axis];
    size += half_side[axis];
  }
  const float4 slack = 1e-5f * (sqrt(length_sq) + sqrt(apex_sq) + size);
  float4 depth_extent = 0, across_sq = 0, across[3];
  for (int axis = 0; axis < 3; ++axis) {
    depth_extent += fabs(light.axis[axis]) * half_side[axis];
    across[axis] = to_center[axis] - along * light.axis[axis];
    across_sq += across[axis] * across[axis];
  }
  const float4 inverse_across = rsqrt(across_sq);
  float4 side_extent = 0;
  for (int axis = 0; axis < 3; ++axis)
    side_extent +=
        fabs(light.cone_cos * across[axis] * inverse_across - light.cone_sin * light.axis[axis]) * half_side[axis];
  const int4 off_axis_meets = light.cone_cos * sqrt(across_sq) - light.cone_sin * along <= side_extent + slack;
  /* a centre on the axis (across_sq = 0) meets the cone whenever it is not in front of the apex */
  return (along + depth_extent >= -slack) & (off_axis_meets | (across_sq == 0));
}

/* Where a light can reach the boxes: a shaded box sharing one of its distance bins, met by its
 * sphere (or it has no range), and for a spot met by its cone. Each test runs only while a box is
 * left. */
int4 reaches_boxes(LightBounds light, const BoxBlock* block) {
  int4 mask = block->shaded & ((light.distance_bins & block->distance_bins) != 0);
  if (light.radius >= 0 && any_box(mask)) mask &= sphere_meets_boxes(light, block);
  if (light.cone_cos > 0 && any_box(mask)) mask &= cone_meets_boxes(light, block);
  return mask;
}

/* Where a light's bounding sphere holds all of each box (its farthest corner inside; no range: every
 * box). Such a light reaches every row of a tile, or nearly (a spot's sphere bounds its cone, not
 * its range), so the shading leaves out its range test per row: a shortcut only, as the window is
 * still taken per pixel. */
int4 sphere_holds_boxes(LightBounds light, const BoxBlock* block) {
  if (light.radius < 0) return (int4)-1;
  float4 farthest_sq = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const float4 farthest =
        fmax(fabs(block->lo[axis] - light.center[axis]), fabs(block->hi[axis] - light.center[axis]));
    farthest_sq += farthest * farthest;
  }
  return farthest_sq <= light.radius * light.radius;
}

/* A box's list as it is written: the lights that hold the box lead it (with lead_holding), from the
 * front of its room, the others from the back. A box with no room (none there, or nothing shaded) is
 * never written. */
typedef struct {
  __global uint* lights;
  uint holding, partial;
  int has_room;
} KeptList;

/* Light k is written to both free ends of the room, and the end it belongs to, if any, is moved on:
 * which of a block's boxes a light reaches follows no pattern a branch predictor learns. Both slots
 * are free, as fewer entries than the room holds are written before the last candidate. */
void keep_where(int lane, int holds, uint k, uint room, KeptList* list) {
  if (!list->has_room) return;
  list->lights[list->holding] = k;
  list->lights[room - 1 - list->partial] = k;
  list->holding += lane && holds;
  list->partial += lane && !holds;
}

/* One work-item per block of four boxes (block_boxes[b]: their indices, PHONGCL_NO_BOX for none).
 * Its candidates are candidates[candidate_first[b] ...], candidate_count[b] of them: every light for
 * the coarsest level, the list of the box one level up (whose 2 x 2 block this is) for the others.
 * The ones that reach box t are written from kept_lights[kept_first[t]], where there is room for all
 * of them, and counted in kept_count[t]. With lead_holding (the tiles' level) the lights whose
 * sphere holds all of the box come first, in order, counted in kept_holding[t], and the rest follow
 * in reverse order: the shading tests only those against its pixels' ranges. Otherwise every light
 * is in order. */
__kernel void keep_box_lights(__global const TileBox* restrict boxes, __global const LightBounds* restrict lights,
                              __global const uint4* restrict block_boxes, __global const uint* restrict candidates,
                              __global const uint* restrict candidate_first,
                              __global const uint* restrict candidate_count, __global const uint* restrict kept_first,
                              __global uint* restrict kept_lights, __global uint* restrict kept_count,
                              uint lead_holding, __global uint* restrict kept_holding) {
  const uint b = get_global_id(0);
  const uint4 index = block_boxes[b];
  const uint slots[4] = {index.s0, index.s1, index.s2, index.s3};
  const BoxBlock block = box_block(boxes, slots);
  KeptList kept[4];
  for (int s = 0; s < 4; ++s) {
    kept[s].has_room = slots[s] != PHONGCL_NO_BOX && boxes[slots[s]].shaded > 0;
    kept[s].lights = kept_lights + (slots[s] == PHONGCL_NO_BOX ? 0 : kept_first[slots[s]]);
    kept[s].holding = kept[s].partial = 0;
  }
  const uint room = candidate_count[b];
  const uint first = candidate_first[b], end = any_box(block.shaded) ? first + room : first;
  for (uint j = first; j < end; ++j) {
    const uint k = candidates[j];
    const int4 mask = reaches_boxes(lights[k], &block);
    if (!any_box(mask)) continue;
    /* Without lead_holding every light is "holding": written in order from the front. */
    const int4 holds = lead_holding ? sphere_holds_boxes(lights[k], &block) : (int4)-1;
    keep_where(mask.s0, holds.s0, k, room, &kept[0]);
    keep_where(mask.s1, holds.s1, k, room, &kept[1]);
    keep_where(mask.s2, holds.s2, k, room, &kept[2]);
    keep_where(mask.s3, holds.s3, k, room, &kept[3]);
  }
  for (int s = 0; s < 4; ++s) {
    if (slots[s] == PHONGCL_NO_BOX) continue;
    /* The rest down to just after the holding ones: the copy never overwrites an entry before reading it. */
    __global uint* list = kept[s].lights;
    for (uint i = 0; i < kept[s].partial; ++i) list[kept[s].holding + i] = list[room - kept[s].partial + i];
    kept_count[slots[s]] = kept[s].holding + kept[s].partial;
    if (lead_holding) kept_holding[slots[s]] = kept[s].holding;
  }
}
