// The render's tiles: a grid of rectangles covering a region, row by row. The tile list is made
// once per render; the tile loop and the splat film (which must know which pixels lie wholly in
// one tile) both read this list rather than each recomputing the grid from a tile size.
#pragma once

#include <vector>

#include "render/film.h"

namespace kiln {

// Tiles of size × size pixels over region (the last column and row narrower), aligned at the
// region's corner, in raster order of the tiles.
std::vector<pixel_rect> make_tiles(const pixel_rect& region, int size);

// The same tiles moved by (dx, dy): frame coordinates to a film's own.
std::vector<pixel_rect> shifted(std::vector<pixel_rect> tiles, int dx, int dy);

}  // namespace kiln
