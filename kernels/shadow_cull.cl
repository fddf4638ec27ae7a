/* Tiled shadow culling, before shading (or tracing): per screen tile and shadow-casting light, the
 * primitives and the planes that can block any of the tile's shadow rays toward that light
 * (ShadowCandidate, shadow_layout.h), so that a pixel tests a few primitives instead of traversing:
 *   merge_tile_boxes         the boxes of the coarse level's tiles, from the tiles' (cull.cl)
 *   count_shadow_candidates  one work-item per (light, tile): how many, or PHONGCL_SHADOW_TRAVERSE
 *   fill_shadow_candidates   the same walk again, writing them at the host's offset for the pair
 *   collect_shadow_candidates  the tiles' level in one pass, in room the parent's count bounds
 * (pair p = light * tile_count + tile). A tile's rays start within its box of shaded positions
 * (TileBox, cull.cl's tile_bounds) grown by the largest offset there (shadow.h), so every ray lies
 * in the convex hull of that box and a point light, or of the box swept along a directional light's
 * l: whatever misses the hull blocks none of them. The hull tests below are exact for boxes, and
 * widened by 2^-18 of the magnitudes involved against float rounding: culling may keep what it
 * could drop, never the other way round. */
#include "bvh.h"
#include "layout.h"
#include "tiles.h"

/* The boxes of a coarser grid, each the union of the ratio x ratio tile boxes it covers (`fine`
 * holds fine_tiles_x boxes per row), so the coarse level needs no second pass over the G-buffer. */
__kernel void merge_tile_boxes(__global const TileBox* restrict fine, const uint fine_tiles_x, const uint fine_tiles,
                               const uint ratio, const uint coarse_tiles_x, __global TileBox* restrict coarse) {
  const uint tile = get_global_id(0);
  const uint fine_rows = fine_tiles / fine_tiles_x;
  const uint x0 = tile % coarse_tiles_x * ratio, y0 = tile / coarse_tiles_x * ratio;
  TileBox box = empty_tile_box();
  for (uint y = y0; y < min(y0 + ratio, fine_rows); ++y)
    for (uint x = x0; x < min(x0 + ratio, fine_tiles_x); ++x) add_to_box(&box, fine[y * fine_tiles_x + x]);
  coarse[tile] = box;
}

/* The hull at parameter s is a box: centre c + s d, half size h - s k (a point light: d = L - c,
 * k = h - e for a light box of half size e, s in [0, 1]: the convex hull of the tile's box and the
 * light's; a directional light: d = l, k = 0, s >= 0). */
typedef struct {
  float centre[3], half_size[3], toward[3], shrink[3];
  float s_max;
} ShadowHull;

static inline ShadowHull tile_hull(const TileBox* box, ShadowLight light, float offset_scale, float eye_extent) {
  ShadowHull hull;
  float largest = 0;
  for (int axis = 0; axis < 3; ++axis) largest = fmax(largest, fmax(fabs(box->lo[axis]), fabs(box->hi[axis])));
  const float grow = offset_scale * (largest + eye_extent);
  for (int axis = 0; axis < 3; ++axis) {
    hull.centre[axis] = 0.5f * (box->lo[axis] + box->hi[axis]);
    hull.half_size[axis] = 0.5f * (box->hi[axis] - box->lo[axis]) + grow;
    hull.toward[axis] = light.directional ? light.where[axis] : light.where[axis] - hull.centre[axis];
    hull.shrink[axis] = light.directional ? 0 : hull.half_size[axis] - light.half_extent[axis];
  }
  hull.s_max = light.directional ? INFINITY : 1;
  return hull;
}

/* Whether some s in [0, s_max] has |c + s d - cn| <= h - s k + hn on every axis: per axis two
 * linear inequalities in s, s (d + k) <= H - a and s (k - d) <= H + a (a = c - cn, H = h + hn). */
static inline bool hull_meets_box(const ShadowHull* hull, const float lo[3], const float hi[3]) {
  float s_lo = 0, s_hi = hull->s_max;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(lo[axis] <= hi[axis])) return false; /* an empty box */
    const float centre = 0.5f * (lo[axis] + hi[axis]), half_size = 0.5f * (hi[axis] - lo[axis]);
    const float d = hull->toward[axis], k = hull->shrink[axis];
    const float margin = 0x1p-18f * (fabs(hull->centre[axis]) + fabs(centre) + hull->half_size[axis] + half_size + fabs(d));
    const float a = hull->centre[axis] - centre, reach = hull->half_size[axis] + half_size + margin;
    const float slope[2] = {d + k, k - d}, bound[2] = {reach - a, reach + a};
    for (int side = 0; side < 2; ++side) {
      if (slope[side] > 0) s_hi = fmin(s_hi, bound[side] / slope[side]);
      else if (slope[side] < 0) s_lo = fmax(s_lo, bound[side] / slope[side]);
      else if (bound[side] < 0) return false;
    }
  }
  return s_lo <= s_hi;
}

/* Whether the plane can cut the hull: the signed distances of the box's corners lie in
 * [middle - spread, middle + spread]; the light's (a point light, within its box's light_spread) or
 * the sweep's direction (a directional light) must not put the whole hull on one side. */
static inline bool hull_meets_plane(const ShadowHull* hull, __global const ShadowPlane* plane, ShadowLight light) {
  float middle = -plane->offset, spread = 0, size = fabs(plane->offset), along = 0, light_spread = 0;
  for (int axis = 0; axis < 3; ++axis) {
    middle += plane->normal[axis] * hull->centre[axis];
    spread += fabs(plane->normal[axis]) * hull->half_size[axis];
    light_spread += fabs(plane->normal[axis]) * light.half_extent[axis];
    size += fabs(plane->normal[axis]) * (fabs(hull->centre[axis]) + fabs(light.where[axis]));
    along += plane->normal[axis] * light.where[axis];
  }
  const float margin = 0x1p-18f * (size + spread);
  if (light.directional) {
    if (middle - spread > margin && along >= 0) return false; /* above, moving away */
    if (middle + spread < -margin && along <= 0) return false;
    return true;
  }
  const float at_light = along - plane->offset;
  if (middle - spread > margin && at_light - light_spread > margin) return false;
  if (middle + spread < -margin && at_light + light_spread < -margin) return false;
  return true;
}

/* A list being written (out null: only counted); full once it would pass `limit`. */
typedef struct {
  __global ShadowCandidate* out;
  uint count, limit;
} CandidateList;

static inline bool add_run(CandidateList* list, uint first, uint kind, uint count) {
  if (list->count == list->limit) return false;
  if (list->out) {
    list->out[list->count].first = first;
    list->out[list->count].kind_count = kind | count << PHONGCL_BVH_KIND_BITS;
  }
  ++list->count;
  return true;
}

/* The primitives of a leaf whose own boxes meet the hull, neighbours merged into runs. */
static inline bool add_leaf(CandidateList* list, const ShadowHull* hull, __global const ShadowBounds* bounds, uint first,
                            uint kind_count) {
  const uint kind = kind_count & PHONGCL_BVH_KIND_MASK, end = first + (kind_count >> PHONGCL_BVH_KIND_BITS);
  uint run = first, run_count = 0;
  for (uint k = first; k < end; ++k) {
    const ShadowBounds box = bounds[k];
    if (hull_meets_box(hull, box.lo, box.hi)) {
      if (run_count == 0) run = k;
      ++run_count;
    } else if (run_count > 0) {
      if (!add_run(list, run, kind, run_count)) return false;
      run_count = 0;
    }
  }
  return run_count == 0 || add_run(list, run, kind, run_count);
}

/* The planes and the BVH's primitives that meet the hull; false once the list is full. */
static bool walk_bvh(CandidateList* list, const ShadowHull* hull, ShadowLight light, __global const BvhNode* nodes,
                     uint node_count, __global const ShadowBounds* bounds, __global const ShadowPlane* planes,
                     uint plane_count) {
  for (uint k = 0; k < plane_count; ++k)
    if (hull_meets_plane(hull, &planes[k], light) && !add_run(list, k, BVH_PLANES, 1)) return false;
  if (node_count == 0) return true;
  BvhWalk walk = {.size = 0, .node = 0};
  for (;;) {
    __global const BvhNode* record = &nodes[walk.node];
    int enter[2];
    for (int c = 0; c < 2; ++c) {
      const float lo[3] = {record->lo_x[c], record->lo_y[c], record->lo_z[c]};
      const float hi[3] = {record->hi_x[c], record->hi_y[c], record->hi_z[c]};
      enter[c] = hull_meets_box(hull, lo, hi);
      const uint kind_count = record->kind_count[c];
      if (enter[c] && (kind_count & PHONGCL_BVH_KIND_MASK) != BVH_INNER) {
        enter[c] = 0;
        if (!add_leaf(list, hull, bounds, record->first[c], kind_count)) return false;
      }
    }
    if (!next_node(&walk, record, enter)) return true;
  }
}

/* The entries of a larger tile's list (which holds every candidate of this one) that meet the hull. */
static bool filter_list(CandidateList* list, const ShadowHull* hull, ShadowLight light,
                        __global const ShadowCandidate* parent, uint parent_count, __global const ShadowBounds* bounds,
                        __global const ShadowPlane* planes) {
  for (uint j = 0; j < parent_count; ++j) {
    const uint first = parent[j].first, kind_count = parent[j].kind_count;
    if ((kind_count & PHONGCL_BVH_KIND_MASK) == BVH_PLANES) {
      if (hull_meets_plane(hull, &planes[first], light) && !add_run(list, first, BVH_PLANES, 1)) return false;
    } else if (!add_leaf(list, hull, bounds, first, kind_count)) {
      return false;
    }
  }
  return true;
}

/* The candidates of one (light, tile) pair (pair = light * tiles + tile, at every level), written to
 * `out` (null: counted); their number, or PHONGCL_SHADOW_TRAVERSE beyond the limit. They come from
 * the level above (CullLevel, shadow_layout.h), whose list holds all of them, or from the BVH where
 * there is none or it went beyond its limit. */
static uint pair_candidates(uint pair, uint tile_count, __global const TileBox* boxes, __global const ShadowLight* lights,
                            float offset_scale, float eye_extent, CullLevel level, __global const uint* parent_counts,
                            __global const uint* parent_offsets, __global const ShadowCandidate* parent_candidates,
                            __global const BvhNode* nodes, uint node_count, __global const ShadowBounds* bounds,
                            __global const ShadowPlane* planes, uint plane_count, __global ShadowCandidate* out,
                            uint limit) {
  const uint tile = pair % tile_count, light_index = pair / tile_count;
  const TileBox box = boxes[tile];
  if (box.shaded == 0) return 0;
  const ShadowLight light = lights[light_index];
  const ShadowHull hull = tile_hull(&box, light, offset_scale, eye_extent);
  uint parent_count = PHONGCL_SHADOW_TRAVERSE, parent_pair = 0;
  if (level.ratio > 0) {
    const uint parent = (tile / level.tiles_x / level.ratio) * level.parent_tiles_x + tile % level.tiles_x / level.ratio;
    parent_pair = light_index * level.parent_tiles + parent;
    parent_count = parent_counts[parent_pair];
  }
  /* The room the host gave a tile is its parent's count; a parent's run may split here (some of its
   * primitives miss the tile), so a list that would outgrow the room traverses instead. */
  CandidateList list = {out, 0, parent_count == PHONGCL_SHADOW_TRAVERSE ? limit : min(limit, parent_count)};
  const bool complete = parent_count == PHONGCL_SHADOW_TRAVERSE
                            ? walk_bvh(&list, &hull, light, nodes, node_count, bounds, planes, plane_count)
                            : filter_list(&list, &hull, light, &parent_candidates[parent_offsets[parent_pair]],
                                          parent_count, bounds, planes);
  return complete ? list.count : PHONGCL_SHADOW_TRAVERSE;
}

__kernel void count_shadow_candidates(__global const TileBox* restrict boxes, const uint tile_count,
                                      __global const ShadowLight* restrict lights, const float offset_scale,
                                      const float eye_extent, const uint limit,
                                      /* the level above (ratio 0: none) */
                                      const CullLevel level, __global const uint* restrict parent_counts,
                                      __global const uint* restrict parent_offsets,
                                      __global const ShadowCandidate* restrict parent_candidates,
                                      /* the shadow geometry (shadow_layout.h) */
                                      __global const BvhNode* restrict nodes, const uint node_count,
                                      __global const ShadowBounds* restrict bounds,
                                      __global const ShadowPlane* restrict planes, const uint plane_count,
                                      __global uint* restrict counts) {
  const uint pair = get_global_id(0);
  counts[pair] = pair_candidates(pair, tile_count, boxes, lights, offset_scale, eye_extent, level, parent_counts,
                                 parent_offsets, parent_candidates, nodes, node_count, bounds, planes, plane_count, 0,
                                 limit);
}

/* The tiles' level in one pass: a tile's list is part of its parent's, so the host gives each pair
 * room for min(its parent's count, limit) entries (limit where the parent traverses) and the walk
 * writes its list and count at once. */
__kernel void collect_shadow_candidates(__global const TileBox* restrict boxes, const uint tile_count,
                                        __global const ShadowLight* restrict lights, const float offset_scale,
                                        const float eye_extent, const uint limit, const CullLevel level,
                                        __global const uint* restrict parent_counts,
                                        __global const uint* restrict parent_offsets,
                                        __global const ShadowCandidate* restrict parent_candidates,
                                        __global const BvhNode* restrict nodes, const uint node_count,
                                        __global const ShadowBounds* restrict bounds,
                                        __global const ShadowPlane* restrict planes, const uint plane_count,
                                        __global const uint* restrict offsets, __global uint* restrict counts,
                                        __global ShadowCandidate* restrict candidates) {
  const uint pair = get_global_id(0);
  counts[pair] = pair_candidates(pair, tile_count, boxes, lights, offset_scale, eye_extent, level, parent_counts,
                                 parent_offsets, parent_candidates, nodes, node_count, bounds, planes, plane_count,
                                 &candidates[offsets[pair]], limit);
}

__kernel void fill_shadow_candidates(__global const TileBox* restrict boxes, const uint tile_count,
                                     __global const ShadowLight* restrict lights, const float offset_scale,
                                     const float eye_extent, const CullLevel level,
                                     __global const uint* restrict parent_counts,
                                     __global const uint* restrict parent_offsets,
                                     __global const ShadowCandidate* restrict parent_candidates,
                                     __global const BvhNode* restrict nodes, const uint node_count,
                                     __global const ShadowBounds* restrict bounds,
                                     __global const ShadowPlane* restrict planes, const uint plane_count,
                                     __global const uint* restrict counts, __global const uint* restrict offsets,
                                     __global ShadowCandidate* restrict candidates) {
  const uint pair = get_global_id(0);
  if (counts[pair] == 0 || counts[pair] == PHONGCL_SHADOW_TRAVERSE) return;
  pair_candidates(pair, tile_count, boxes, lights, offset_scale, eye_extent, level, parent_counts, parent_offsets,
                  parent_candidates, nodes, node_count, bounds, planes, plane_count, &candidates[offsets[pair]],
                  counts[pair]);
}
