#include "render/tile_grid.h"

#include <algorithm>

namespace kiln {

std::vector<pixel_rect> make_tiles(const pixel_rect& region, int size) {
  std::vector<pixel_rect> tiles;
  for (int y = region.y0; y < region.y1; y += size)
    for (int x = region.x0; x < region.x1; x += size)
      tiles.push_back({x, y, std::min(x + size, region.x1), std::min(y + size, region.y1)});
  return tiles;
}

std::vector<pixel_rect> shifted(std::vector<pixel_rect> tiles, int dx, int dy) {
  for (pixel_rect& t : tiles) t = {t.x0 + dx, t.y0 + dy, t.x1 + dx, t.y1 + dy};
  return tiles;
}

}  // namespace kiln
