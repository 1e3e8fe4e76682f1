// Filtered reconstruction whose bytes do not depend on threads or tile size. Each pixel's value is
// a left fold, in raster order of the source pixels within the filter's reach, of what each source
// pixel's samples contribute to it (P(q→p), summed in sample order). A pixel whose reach lies in
// one tile is folded by that tile as it renders (it visits the sources in raster order); a pixel
// near a tile border keeps one slot per source and is folded after the parallel loop. Float
// additions therefore happen in one order for any schedule. Depends on core and render only.
#pragma once

#include "render/film.h"
#include "render/id_coverage.h"
#include "render/reconstruction_filter.h"

#include <cstdint>
#include <vector>

namespace kiln {

// One source pixel's contributions to the (2·reach+1)² pixels around it, rows top to bottom.
struct pixel_splat {
  int reach = 0;
  std::vector<dvec4> sum;     // Σ w·(premultiplied colour, alpha) over the source's samples
  std::vector<float> weight;  // Σ w
  // Per Cryptomatte layer asked for, Σ w of the samples that hit each id (else empty).
  std::vector<id_weights> ids[matte_layer_count];
  // With the light split: Σ w·(direct, reflection, refraction), three per window pixel (else empty).
  std::vector<dvec3> split;

  explicit pixel_splat(int r = 0, const bool (&layers)[matte_layer_count] = {}, bool with_split = false);
  void clear();
  // Adds one sample taken at offset (each coordinate in [0, 1)) inside the source pixel; sample_ids
  // holds its id in each layer, or is null for a sample that hit nothing (it only adds weight).
  // sample_split is its colour by first event, (direct, reflection, refraction), used when the
  // splat keeps the split.
  void add(const reconstruction_filter& f, vec2 offset, const vec4& value,
           const uint32_t* sample_ids = nullptr, const vec3* sample_split = nullptr);
};

class splat_film {
 public:
  // layers: the Cryptomatte layers whose id weights are folded beside the colour.
  splat_film(int width, int height, int tile_size, const reconstruction_filter& f,
             const bool (&layers)[matte_layer_count] = {}, bool with_split = false);

  int reach() const { return reach_; }

  // Hands over source pixel (x, y)'s contributions. Within a tile, call in raster order; pixels of
  // different tiles may be added concurrently.
  void add(int x, int y, const pixel_splat& splat);

  // Writes colour = Σ w·L / Σ w into out (0 where no sample has weight), and each Cryptomatte
  // layer's ranks with coverage = Σ w (hits of the id) / Σ w: the same weights and the same fold
  // as the colour, so coverage sums to alpha where the background is transparent. Call after
  // every add().
  void resolve(film& out) const;

 private:
  bool within_one_tile(int x, int y) const;

  int width_, height_, tile_size_, reach_, window_;
  // Sums in double: a few very bright samples (near the float maximum) must not overflow a pixel
  // to +inf although each sample and their mean are finite.
  std::vector<dvec4> sum_;  // pixels folded by their own tile
  std::vector<float> weight_;
  std::vector<int64_t> slot_of_;  // first slot of a tile-border pixel; -1 elsewhere
  std::vector<dvec4> slot_sum_;   // per border pixel, one slot per source, raster order
  std::vector<float> slot_weight_;
  // Cryptomatte layers, laid out like sum_ and slot_sum_; empty for a layer not asked for.
  std::vector<id_weights> id_sum_[matte_layer_count];
  std::vector<id_weights> slot_ids_[matte_layer_count];
  // The light split, three per pixel and per slot; empty when not asked for.
  std::vector<dvec3> split_sum_;
  std::vector<dvec3> slot_split_;
};

}  // namespace kiln
