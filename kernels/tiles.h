/* Which culling tile a work-item belongs to (TileGrid in layout.h): the tile of its first pixel;
 * and the union of tile boxes (TileBox), for the culling kernels' coarser levels. */
#ifndef PHONGCL_TILES_H
#define PHONGCL_TILES_H

#include "layout.h"

uint tile_of_pixel(TileGrid grid, uint pixel) {
  const uint x = pixel % grid.image_width, y = pixel / grid.image_width;
  return (y / grid.tile_rows) * grid.tiles_x + x / grid.tile_size;
}

/* A box with no point in it: the union's identity, as tile_bounds leaves a tile with nothing shaded. */
TileBox empty_tile_box(void) {
  const TileBox box = {{INFINITY, INFINITY, INFINITY}, 0, {-INFINITY, -INFINITY, -INFINITY}, 0};
  return box;
}

void add_to_box(TileBox* box, TileBox part) {
  for (int axis = 0; axis < 3; ++axis) {
    box->lo[axis] = fmin(box->lo[axis], part.lo[axis]);
    box->hi[axis] = fmax(box->hi[axis], part.hi[axis]);
  }
  box->shaded += part.shaded;
  box->distance_bins |= part.distance_bins;
}

#endif
