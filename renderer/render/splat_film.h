// Filtered reconstruction whose bytes do not depend on threads or tile size. Each pixel's value is
// a left fold, in raster order of the source pixels within the filter's reach, of what each source
// pixel's samples contribute to it (P(q→p), summed in sample order). A pixel whose reach lies in
// one tile is folded by that tile as it renders, in a tile-sized accumulator (it visits the sources
// in raster order), and resolved when the tile ends; a pixel near a tile border keeps one slot per
// source and is folded after the parallel loop. Float
// additions therefore happen in one order for any schedule. Depends on core and render only.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film.h"
#include "render/id_coverage.h"
#include "render/reconstruction_filter.h"

namespace kiln {

// One source pixel's contributions to the (2·reach+1)² pixels around it, rows top to bottom.
struct pixel_splat {
  int reach = 0;
  std::vector<dvec4> sum;     // Σ w·(premultiplied colour, alpha) over the source's samples
  std::vector<float> weight;  // Σ w
  // Per Cryptomatte layer asked for, Σ w of the samples that hit each id (else empty).
  std::vector<id_weights> ids[matte_layer_count];
  // The beauty's parts (render/aov_list.h's beauty_part_count: the light split, then the light
  // groups): Σ w·part, `part_count` per window pixel (else empty).
  int part_count = 0;
  std::vector<dvec3> parts;

  explicit pixel_splat(int r = 0, const bool (&layers)[matte_layer_count] = {}, int part_count = 0);
  void clear();
  // Adds one sample taken at offset (each coordinate in [0, 1)) inside the source pixel; mattes
  // holds the ids it covers in each layer with their coverage, or is null for a sample that hit
  // nothing (it only adds weight): an id's weight grows by w × its coverage.
  // sample_parts holds its part_count parts of the colour, used when the splat keeps parts.
  void add(const reconstruction_filter& f, vec2 offset, const vec4& value,
           const sample_mattes* mattes = nullptr, const vec3* sample_parts = nullptr);
};

// The sums of the pixels one tile folds itself (those whose whole reach lies in the tile), laid
// out over the tile alone: tile-sized, so it stays in cache, and the film needs no full-frame
// accumulator for them. One per render task, reused tile after tile (see splat_film::begin_tile).
class tile_sums {
 private:
  friend class splat_film;
  int x0 = 0, y0 = 0, width = 0, height = 0;  // the tile, in film coordinates
  std::vector<dvec4> sum;
  std::vector<float> weight;
  std::vector<id_weights> ids[matte_layer_count];
  std::vector<dvec3> parts;
  size_t index(int x, int y) const { return size_t(y - y0) * width + (x - x0); }
};

// Writes a pixel's resolved beauty parts (beauty_part_count of them, in its order) into the film's
// light split and light group buffers that exist.
void store_beauty_parts(film& out, size_t p, const vec3* parts);

class splat_film {
 public:
  // tiles: the render's tiles in film coordinates (render/tile_grid.h), a grid of columns and
  // rows covering the film; a pixel folds in its tile when its whole reach lies in that tile.
  // layers: the Cryptomatte layers whose id weights are folded beside the colour; part_count: the
  // beauty's parts folded beside it (the light split's three, then the light groups: see
  // store_pixel in the source for where each goes).
  splat_film(int width, int height, const std::vector<pixel_rect>& tiles, const reconstruction_filter& f,
             const bool (&layers)[matte_layer_count] = {}, int part_count = 0);

  int reach() const { return reach_; }

  // Starts tile (one of the list given at construction, film coordinates) in t.
  void begin_tile(tile_sums& t, const pixel_rect& tile) const;
  // Hands over source pixel (x, y)'s contributions; (x, y) lies in t's tile. Within a tile, call
  // in raster order; pixels of different tiles may be added concurrently.
  void add(int x, int y, const pixel_splat& splat, tile_sums& t);
  // Resolves t's tile's own pixels into out (as resolve() describes), after its last add().
  void finish_tile(const tile_sums& t, film& out) const;

  // Writes colour = Σ w·L / Σ w into out (0 where no sample has weight), and each Cryptomatte
  // layer's ranks with coverage = Σ w (hits of the id) / Σ w: the same weights and the same fold
  // as the colour, so coverage sums to alpha where the background is transparent. This resolves
  // the tile-border pixels; call after every tile's finish_tile().
  void resolve(film& out) const;

 private:
  bool within_one_tile(int x, int y) const;

  int width_, height_, reach_, window_;
  // The tiles as a grid: the first column of each pixel column's tile, the first row of each pixel
  // row's tile.
  std::vector<int> column_start_, row_start_;
  bool layers_[matte_layer_count] = {};
  int parts_ = 0;
  // Sums in double: a few very bright samples (near the float maximum) must not overflow a pixel
  // to +inf although each sample and their mean are finite.
  std::vector<int64_t> slot_of_;  // first slot of a tile-border pixel; -1 elsewhere (empty: none)
  int64_t slot_of(size_t p) const { return slot_of_.empty() ? -1 : slot_of_[p]; }
  std::vector<dvec4> slot_sum_;  // per border pixel, one slot per source, raster order
  std::vector<float> slot_weight_;
  // Cryptomatte layers, laid out like slot_sum_; empty for a layer not asked for.
  std::vector<id_weights> slot_ids_[matte_layer_count];
  // The beauty's parts, parts_ per slot; empty when none.
  std::vector<dvec3> slot_parts_;
};

}  // namespace kiln
