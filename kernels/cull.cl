/* Tiled light culling (Andersson 2009; ISPC's examples/cpu/deferred), before phong_shade:
 *   tile_bounds      one work-item per tile: the box of its shaded positions, in lane vectors
 *   keep_box_lights  one work-item per block of boxes: its candidate lights that can reach each box,
 *                    those holding the box first
 * The host runs the last once per level: boxes of 8 x 8 square tiles with every light a candidate,
 * then boxes of 4 x 4 and 2 x 2 of them and then the tiles (the half tiles where the size is even),
 * each with its parent box's list (the parent being the box one level up that the block makes;
 * shading/tile_culling.cpp). Each box writes its list where the host left room for all of its
 * candidates, so every light is tested once per level and no list is compacted: the shading reads
 * the tiles' lists where they are. A light reaches a box when its bounding sphere (LightBounds,
 * widened on the host against rounding) meets it, or when it has no range, and for a spot when its
 * cone can too, and when it spans one of the distance bins of the box's positions (layout.h). The
 * tile of a work-item is the tile of its first pixel (tiles.h), so a tile's box covers every pixel
 * its work-items shade.
 * The small fixed loops (the three axes, a block's boxes, the sieve's eight lights) are unrolled by
 * pragma, a hint for speed alone (docs/kernel.md, "Unrolling"): PoCL's compiler left them rolled,
 * with the arrays they index in memory, and the culling took longer (docs/kernel.md, "Measured").
 * Options: PHONGCL_LANES and HALF_STORAGE, as phong_shade's; PHONGCL_BLOCK_BOXES, the boxes of a
 * block (4 or 8). */
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

/* The box of the shaded positions the work-items of one tile shade: for each of its rows, those whose
 * first pixel is in [row + x_begin, row + x_end). Those slots begin and end at multiples of
 * PHONGCL_LANES (so does first_pixel), so the box is taken over whole lane vectors, background lanes
 * left out by selects, and the lanes reduced once per tile. The sums are named vectors, not arrays
 * indexed by axis, and min and max, not fmin and fmax (no NaN comes here: a shaded position is
 * finite): PoCL kept indexed arrays in memory, and the pass took twice as long (docs/kernel.md,
 * "Measured"). */
__kernel void tile_bounds(__global const STORAGE* restrict planes, uint plane_stride,
                          __global const int* restrict material_index, uint slot_count, TileGrid grid,
                          __global TileBox* restrict boxes) {
  const uint tile = get_global_id(0);
  const uint tile_x = tile % grid.tiles_x, tile_y = tile / grid.tiles_x;
  const uint x_begin = tile_x * grid.tile_size, x_end = min(x_begin + grid.tile_size, grid.image_width);
  floatv lo_x = (floatv)INFINITY, lo_y = lo_x, lo_z = lo_x, hi_x = -lo_x, hi_y = hi_x, hi_z = hi_x;
  intv shaded = (intv)0, distance_bins = (intv)0;
  for (uint y = tile_y * grid.tile_rows; y < (tile_y + 1) * grid.tile_rows; ++y) {
    const ulong row = (ulong)y * grid.image_width;
    const ulong begin = max((ulong)round_up_lanes(row + x_begin), (ulong)grid.first_pixel);
    const ulong end = min((ulong)round_up_lanes(row + x_end), (ulong)grid.first_pixel + slot_count);
    for (ulong pixel = begin; pixel < end; pixel += PHONGCL_LANES) {
      const uint chunk = (uint)((pixel - grid.first_pixel) / PHONGCL_LANES);
      const intv is_shaded = VLOAD(chunk, material_index) != PHONGCL_BACKGROUND;
      const intv one_if_shaded = select((intv)0, (intv)1, is_shaded);
      shaded += one_if_shaded;
      const floatv px = load_plane(planes, plane_stride, PLANE_PX, chunk);
      const floatv py = load_plane(planes, plane_stride, PLANE_PX + 1, chunk);
      const floatv pz = load_plane(planes, plane_stride, PLANE_PX + 2, chunk);
      lo_x = min(lo_x, select((floatv)INFINITY, px, is_shaded));
      lo_y = min(lo_y, select((floatv)INFINITY, py, is_shaded));
      lo_z = min(lo_z, select((floatv)INFINITY, pz, is_shaded));
      hi_x = max(hi_x, select((floatv)-INFINITY, px, is_shaded));
      hi_y = max(hi_y, select((floatv)-INFINITY, py, is_shaded));
      hi_z = max(hi_z, select((floatv)-INFINITY, pz, is_shaded));
      const floatv distance_sq = px * px + py * py + pz * pz;
      const intv bin = (AS_INTV(distance_sq) >> PHONGCL_DISTANCE_BIN_SHIFT) & 31;
      distance_bins |= AS_INTV(AS_UINTV(one_if_shaded) << AS_UINTV(bin)); /* unsigned: bit 31 is no overflow */
    }
  }
  TileBox box;
  box.lo[0] = REDUCE_LANES(lo_x, min), box.lo[1] = REDUCE_LANES(lo_y, min), box.lo[2] = REDUCE_LANES(lo_z, min);
  box.hi[0] = REDUCE_LANES(hi_x, max), box.hi[1] = REDUCE_LANES(hi_y, max), box.hi[2] = REDUCE_LANES(hi_z, max);
  box.shaded = (uint)REDUCE_LANES(shaded, PLUS);
  box.distance_bins = (uint)REDUCE_LANES(distance_bins, BIT_OR);
  boxes[tile] = box;
}

/* Boxes side by side, tested together against one light: a block of one level's grid
 * (tile_culling.cpp), so that each candidate light is read once per block and tested in one vector.
 * PHONGCL_BLOCK_BOXES is 4 (2 x 2 boxes) or 8 (2 x 4 half tiles). A slot with no box holds an empty
 * one (nothing shaded: it keeps nothing). The tests take max rather than fmax: centres are finite and
 * bounds finite or, in an empty box, infinite, so no NaN arises, and fmax's NaN rule costs
 * instructions. */
#if PHONGCL_BLOCK_BOXES == 8
typedef float8 floatb;
typedef int8 intb;
typedef uint8 uintb;
#define VLOAD_BOXES vload8
#define VSTORE_BOXES vstore8
#define AS_UINTB as_uint8
int any_box(intb mask) {
  const int4 either = mask.lo | mask.hi;
  return (either.s0 | either.s1 | either.s2 | either.s3) != 0;
}
#elif PHONGCL_BLOCK_BOXES == 4
typedef float4 floatb;
typedef int4 intb;
typedef uint4 uintb;
#define VLOAD_BOXES vload4
#define VSTORE_BOXES vstore4
#define AS_UINTB as_uint4
int any_box(intb mask) { return (mask.s0 | mask.s1 | mask.s2 | mask.s3) != 0; }
#else
#error "cull.cl needs PHONGCL_BLOCK_BOXES defined, 4 or 8"
#endif

typedef struct {
  floatb lo[3], hi[3];
  uintb distance_bins;
  intb shaded; /* -1 where the box has a shaded pixel, 0 elsewhere */
} BoxBlock;

BoxBlock box_block(__global const TileBox* boxes, const uint slots[PHONGCL_BLOCK_BOXES]) {
  float lo[3][PHONGCL_BLOCK_BOXES], hi[3][PHONGCL_BLOCK_BOXES];
  uint distance_bins[PHONGCL_BLOCK_BOXES], shaded[PHONGCL_BLOCK_BOXES];
#pragma unroll
  for (int s = 0; s < PHONGCL_BLOCK_BOXES; ++s) {
    const TileBox box = slots[s] == PHONGCL_NO_BOX ? empty_tile_box() : boxes[slots[s]];
#pragma unroll
    for (int axis = 0; axis < 3; ++axis) lo[axis][s] = box.lo[axis], hi[axis][s] = box.hi[axis];
    distance_bins[s] = box.distance_bins;
    shaded[s] = box.shaded;
  }
  BoxBlock block;
#pragma unroll
  for (int axis = 0; axis < 3; ++axis) {
    block.lo[axis] = VLOAD_BOXES(0, lo[axis]);
    block.hi[axis] = VLOAD_BOXES(0, hi[axis]);
  }
  block.distance_bins = VLOAD_BOXES(0, distance_bins);
  block.shaded = VLOAD_BOXES(0, shaded) > 0;
  return block;
}

/* Where a light's bounding sphere meets the boxes: the squared distance from its centre to each box
 * against its radius squared. */
intb sphere_meets_boxes(LightBounds light, const BoxBlock* block) {
  floatb distance_sq = 0;
#pragma unroll
  for (int axis = 0; axis < 3; ++axis) {
    const floatb outside =
        max(max(block->lo[axis] - light.center[axis], light.center[axis] - block->hi[axis]), 0.0f);
    distance_sq += outside * outside;
  }
  return distance_sq <= light.radius * light.radius;
}

/* Where a spot's cone can meet the boxes. The cone (narrower than a hemisphere) lies behind the
 * plane through its apex across its axis, and behind the plane through its apex that touches it
 * along the side facing a box's centre; a box is out when all of it is in front of either. The slack
 * covers the rounding of the eye-relative floats. */
intb cone_meets_boxes(LightBounds light, const BoxBlock* block) {
  floatb half_side[3], to_center[3], along = 0, length_sq = 0, size = 0;
  float apex_sq = 0;
#pragma unroll
  for (int axis = 0; axis < 3; ++axis) {
    half_side[axis] = 0.5f * (block->hi[axis] - block->lo[axis]);
    to_center[axis] = block->lo[axis] + half_side[axis] - light.apex[axis];
    along += to_center[axis] * light.axis[axis];
    length_sq += to_center[axis] * to_center[axis];
    apex_sq += light.apex[axis] * light.apex[axis];
    size += half_side[axis];
  }
  const floatb slack = 1e-5f * (sqrt(length_sq) + sqrt(apex_sq) + size);
  floatb depth_extent = 0, across_sq = 0, across[3];
#pragma unroll
  for (int axis = 0; axis < 3; ++axis) {
    depth_extent += fabs(light.axis[axis]) * half_side[axis];
    across[axis] = to_center[axis] - along * light.axis[axis];
    across_sq += across[axis] * across[axis];
  }
  const floatb inverse_across = rsqrt(across_sq);
  floatb side_extent = 0;
#pragma unroll
  for (int axis = 0; axis < 3; ++axis)
    side_extent +=
        fabs(light.cone_cos * across[axis] * inverse_across - light.cone_sin * light.axis[axis]) * half_side[axis];
  const intb off_axis_meets = light.cone_cos * sqrt(across_sq) - light.cone_sin * along <= side_extent + slack;
  /* a centre on the axis (across_sq = 0) meets the cone whenever it is not in front of the apex */
  return (along + depth_extent >= -slack) & (off_axis_meets | (across_sq == 0));
}

/* Where a light can reach the boxes: a shaded box sharing one of its distance bins, met by its
 * sphere (or it has no range), and for a spot met by its cone. Each test runs only while a box is
 * left. */
intb reaches_boxes(LightBounds light, const BoxBlock* block) {
  intb mask = block->shaded & ((light.distance_bins & block->distance_bins) != 0);
  if (light.radius >= 0 && any_box(mask)) mask &= sphere_meets_boxes(light, block);
  if (light.cone_cos > 0 && any_box(mask)) mask &= cone_meets_boxes(light, block);
  return mask;
}

/* Where a light's bounding sphere holds all of each box (its farthest corner inside; no range: every
 * box). Such a light reaches every row of a tile, or nearly (a spot's sphere bounds its cone, not
 * its range), so the shading leaves out its range test per row: a shortcut only, as the window is
 * still taken per pixel. */
intb sphere_holds_boxes(LightBounds light, const BoxBlock* block) {
  if (light.radius < 0) return (intb)-1;
  floatb farthest_sq = 0;
#pragma unroll
  for (int axis = 0; axis < 3; ++axis) {
    const floatb farthest =
        max(fabs(block->lo[axis] - light.center[axis]), fabs(block->hi[axis] - light.center[axis]));
    farthest_sq += farthest * farthest;
  }
  return farthest_sq <= light.radius * light.radius;
}

/* The block's lists as they are written: the lights that hold box s lead its list, from the front of
 * its room (kept_lights + first[s] onwards), the others from the back. A box with no room (none
 * there, or nothing shaded) is never written. */
typedef struct {
  uintb first, holding, partial;
  intb has_room;
} KeptLists;

/* Light k is written to both free ends of each box's room, and the end it belongs to, if any, is
 * moved on: which of a block's boxes a light reaches follows no pattern a branch predictor learns.
 * Both slots are free, as fewer entries than the room holds are written before the last candidate. */
void keep_in_boxes(intb reaches, intb holds, uint k, uint room, __global uint* kept_lights, KeptLists* kept) {
  uint front[PHONGCL_BLOCK_BOXES], back[PHONGCL_BLOCK_BOXES];
  int has_room[PHONGCL_BLOCK_BOXES];
  VSTORE_BOXES(kept->first + kept->holding, 0, front);
  VSTORE_BOXES(kept->first + (room - 1) - kept->partial, 0, back);
  VSTORE_BOXES(kept->has_room, 0, has_room);
#pragma unroll
  for (int s = 0; s < PHONGCL_BLOCK_BOXES; ++s)
    if (has_room[s]) kept_lights[front[s]] = k, kept_lights[back[s]] = k;
  kept->holding += AS_UINTB(reaches & holds) & 1;
  kept->partial += AS_UINTB(reaches & ~holds) & 1;
}

/* Light k kept in each box it reaches. */
void keep_if_reaching(__global const LightBounds* lights, uint k, const BoxBlock* block, uint room,
                      __global uint* kept_lights, KeptLists* kept) {
  const intb reaches = reaches_boxes(lights[k], block);
  if (any_box(reaches)) keep_in_boxes(reaches, sphere_holds_boxes(lights[k], block), k, room, kept_lights, kept);
}

/* The union of the boxes in `slots`. */
TileBox union_of_boxes(__global const TileBox* boxes, const uint slots[PHONGCL_BLOCK_BOXES]) {
  TileBox around = empty_tile_box();
#pragma unroll
  for (int s = 0; s < PHONGCL_BLOCK_BOXES; ++s)
    if (slots[s] != PHONGCL_NO_BOX) add_to_box(&around, boxes[slots[s]]);
  return around;
}

/* Which of lights k[0 ... 7] may reach the box `around` (their spheres and distance bins, as
 * reaches_boxes): a sieve tested across eight lights at once, where most lights reach none. */
int8 may_reach(__global const LightBounds* lights, const uint k[8], TileBox around) {
  float center[3][8], radius[8];
  uint distance_bins[8];
#pragma unroll
  for (int i = 0; i < 8; ++i) {
#pragma unroll
    for (int axis = 0; axis < 3; ++axis) center[axis][i] = lights[k[i]].center[axis];
    radius[i] = lights[k[i]].radius;
    distance_bins[i] = lights[k[i]].distance_bins;
  }
  float8 distance_sq = 0;
#pragma unroll
  for (int axis = 0; axis < 3; ++axis) {
    const float8 c = vload8(0, center[axis]);
    const float8 outside = max(max(around.lo[axis] - c, c - around.hi[axis]), 0.0f);
    distance_sq += outside * outside;
  }
  const float8 r = vload8(0, radius);
  return ((vload8(0, distance_bins) & around.distance_bins) != 0) & ((r < 0) | (distance_sq <= r * r));
}

/* One work-item per block of up to eight boxes (block_boxes[b]: their indices, PHONGCL_NO_BOX for
 * none). Its candidates are candidates[candidate_first[b] ...], candidate_count[b] of them: every
 * light for the coarsest level, the list of the box one level up (which this block makes) for the
 * others, the first candidate_holding[b] of which hold all of that box. The ones that reach box t are
 * written from kept_lights[kept_first[t]], where there is room for all of them, and counted in
 * kept_count[t]: the lights whose sphere holds all of the box first, in order, counted in
 * kept_holding[t], and the rest in reverse order. The next level takes a holding light as reaching
 * without testing it (a spot still tests its cone), and the shading tests only the rest against its
 * pixels' ranges. */
__kernel void keep_box_lights(__global const TileBox* restrict boxes, __global const LightBounds* restrict lights,
                              __global const uint* restrict block_boxes, __global const uint* restrict candidates,
                              __global const uint* restrict candidate_first,
                              __global const uint* restrict candidate_count,
                              __global const uint* restrict candidate_holding, __global const uint* restrict kept_first,
                              __global uint* restrict kept_lights, __global uint* restrict kept_count,
                              __global uint* restrict kept_holding, uint sieve) {
  const uint b = get_global_id(0);
  uint slots[PHONGCL_BLOCK_BOXES];
  VSTORE_BOXES(VLOAD_BOXES(b, block_boxes), 0, slots);
  const BoxBlock block = box_block(boxes, slots);
  uint list_first[PHONGCL_BLOCK_BOXES];
  int has_room[PHONGCL_BLOCK_BOXES];
#pragma unroll
  for (int s = 0; s < PHONGCL_BLOCK_BOXES; ++s) {
    has_room[s] = slots[s] != PHONGCL_NO_BOX && boxes[slots[s]].shaded > 0;
    list_first[s] = slots[s] == PHONGCL_NO_BOX ? 0 : kept_first[slots[s]];
  }
  KeptLists kept = {VLOAD_BOXES(0, list_first), 0, 0, VLOAD_BOXES(0, has_room)};
  const uint room = candidate_count[b];
  const uint first = candidate_first[b], end = any_box(block.shaded) ? first + room : first;
  const uint holding_end = min(first + candidate_holding[b], end);
  /* A light holding the parent box holds each of its boxes, and spans the distance bins of every
   * position in them. */
  for (uint j = first; j < holding_end; ++j) {
    const uint k = candidates[j];
    const intb reaches = lights[k].cone_cos > 0 ? block.shaded & cone_meets_boxes(lights[k], &block) : block.shaded;
    keep_in_boxes(reaches, (intb)-1, k, room, kept_lights, &kept);
  }
  uint j = holding_end;
  if (sieve) {
    const TileBox around = union_of_boxes(boxes, slots);
    for (; j + 8 <= end; j += 8) {
      uint k[8];
      int may[8];
      vstore8(vload8(0, candidates + j), 0, k);
      vstore8(may_reach(lights, k, around), 0, may);
#pragma unroll
      for (int i = 0; i < 8; ++i)
        if (may[i]) keep_if_reaching(lights, k[i], &block, room, kept_lights, &kept);
    }
  }
  for (; j < end; ++j) keep_if_reaching(lights, candidates[j], &block, room, kept_lights, &kept);
  uint holding[PHONGCL_BLOCK_BOXES], partial[PHONGCL_BLOCK_BOXES];
  VSTORE_BOXES(kept.holding, 0, holding);
  VSTORE_BOXES(kept.partial, 0, partial);
#pragma unroll
  for (int s = 0; s < PHONGCL_BLOCK_BOXES; ++s) {
    if (slots[s] == PHONGCL_NO_BOX) continue;
    /* The rest down to just after the holding ones: the copy never overwrites an entry before reading it. */
    __global uint* list = kept_lights + list_first[s];
    for (uint i = 0; i < partial[s]; ++i) list[holding[s] + i] = list[room - partial[s] + i];
    kept_count[slots[s]] = holding[s] + partial[s];
    kept_holding[slots[s]] = holding[s];
  }
}
