/* Which culling tile a work-item belongs to (TileGrid in layout.h): the tile of its first pixel. */
#ifndef PHONGCL_TILES_H
#define PHONGCL_TILES_H

#include "layout.h"

uint tile_of_pixel(TileGrid grid, uint pixel) {
  const uint x = pixel % grid.image_width, y = pixel / grid.image_width;
  return (y / grid.tile_size) * grid.tiles_x + x / grid.tile_size;
}

#endif
