// Filtered reconstruction without races: each tile splats its samples into its own buffer (the
// tile grown by the filter's reach, an apron), and the buffers are summed into the image in tile
// index order, so each pixel's float additions happen in one order for any thread count or
// schedule. Depends on core and render only.
#pragma once

#include <vector>

#include "render/film.h"
#include "render/reconstruction_filter.h"

namespace kiln {

// One tile's weighted sums, over the tile plus an apron of `reach` pixels on each side.
struct splat_tile {
  int x0 = 0, y0 = 0;  // image position of the buffer's first pixel (negative in the apron)
  int width = 0, height = 0;
  std::vector<vec4> sum;      // Σ w·(premultiplied colour, alpha)
  std::vector<float> weight;  // Σ w
};

// An empty buffer for the tile covering pixels [x0, x1) × [y0, y1).
splat_tile make_splat_tile(int x0, int y0, int x1, int y1, int reach);

// Adds value, sampled at offset (each coordinate in [0, 1)) inside pixel (px, py), to every
// pixel of t whose centre lies within the filter's support. The pixel must belong to t's tile.
void splat_sample(splat_tile& t, const reconstruction_filter& f, int px, int py, vec2 offset,
                  const vec4& value);

// Sums finished tiles into the image in index order, whatever order they arrive in; a tile's
// buffer is freed once merged. Not thread-safe: callers serialise add().
class ordered_tile_merge {
 public:
  ordered_tile_merge(int width, int height, size_t tile_count);

  // Takes tile `index`; merges it and every waiting successor once all earlier tiles are in.
  void add(size_t index, splat_tile tile);

  // Writes colour = Σ w·L / Σ w into out (0 where no sample has weight). Call after every add().
  void resolve(film& out) const;

 private:
  void merge(const splat_tile& t);

  int width_, height_;
  std::vector<vec4> sum_;
  std::vector<float> weight_;
  std::vector<splat_tile> waiting_;
  std::vector<bool> arrived_;
  size_t next_ = 0;
};

}  // namespace kiln
