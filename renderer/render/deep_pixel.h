// Deep pixels for a deep EXR (io/exr/deep_writer.h): every pixel's samples along its camera paths,
// kept per render tile, and the pure functions that turn one pixel's path surfaces into the samples
// the file stores. Plain data; depends on core and render's film (pixel_rect) only.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "render/film.h"

namespace kiln {

// Samples of one surface (instance) in one pixel merge when, sorted front to back, each starts
// within this fraction of its depth behind the back of the run merged so far: a surface that
// spans a range of depths inside the pixel (a wall seen at a grazing angle) chains into one
// sample, while two layers of one object farther apart than that (the front and back of a BLEND
// sphere) stay two. Merging moves no colour, so a flatten is unchanged by it; what a deep merge
// with another render can get wrong is only the order against a surface lying inside a merged
// sample's [Z, ZBack] (1% of its depth past each gap, so 1 cm at 1 m).
constexpr float deep_merge_tolerance = 0.01f;

// Where a pixel's samples leave less than this of the pixel showing through, what lies behind is
// folded into the sample in front (its colour kept, its depth extending that sample's ZBack):
// dividing by a transmittance that small would only amplify rounding.
constexpr float deep_min_transmittance = 1e-6f;

// One sample of a deep pixel as the file stores it.
struct deep_sample {
  // Premultiplied colour and alpha. While a pixel is collected: the share of the pixel the surface
  // covers (additive: the pixel's samples sum to the flat beauty); after to_over_form: the form
  // deep compositing reads (see there).
  vec4 rgba{0.0f};
  float z = 0.0f;       // front depth, as the Z AOV measures it (--depth-mode)
  float z_back = 0.0f;  // back depth: z for one camera sample, the farthest of those merged
  // The id AOV's ids (glTF node, material, scene instance) as exact integers in floats, and the
  // Cryptomatte id of the node (the bits of the float CryptoObject stores).
  float object = -1.0f;
  float material = -1.0f;
  float instance = -1.0f;
  float crypto_object = 0.0f;
};

// The deep samples of one render tile: the pixels of rect, row by row, each pixel's samples
// from first[i] to first[i + 1].
struct deep_tile {
  pixel_rect rect;
  std::vector<uint32_t> first{0};
  std::vector<deep_sample> samples;
  bool tidy = true;  // every pixel's samples are non-overlapping (deep_samples_tidy)
};

// A deep image: the tiles of the rendered region, row-major, tile_size pixels a side.
struct deep_image {
  pixel_rect region;
  int full_width = 0, full_height = 0;
  int tile_size = 32;
  std::vector<deep_tile> tiles;

  int tiles_across() const { return (region.width() + tile_size - 1) / tile_size; }
  const deep_tile& tile_at(int x, int y) const {
    return tiles[size_t((y - region.y0) / tile_size) * size_t(tiles_across()) +
                 size_t((x - region.x0) / tile_size)];
  }
  uint64_t sample_count() const {
    uint64_t n = 0;
    for (const deep_tile& t : tiles) n += t.samples.size();
    return n;
  }
  bool tidy() const {  // every tile's
    for (const deep_tile& t : tiles)
      if (!t.tidy) return false;
    return true;
  }
};

// The memory a tile's samples hold.
uint64_t deep_tile_bytes(const deep_tile& t);

// Sorts a pixel's additive samples front to back (by z, then z_back, then instance) and merges
// those of one instance as deep_merge_tolerance says: their colours and alphas add, the front
// stays, z_back becomes the farthest.
void merge_deep_samples(std::vector<deep_sample>& samples);

// Turns sorted additive samples into over-form: each one's rgba divided by the transmittance
// 1 - Σ alpha of the samples in front, so that compositing front to back with `over`
// (C += T·c, T *= 1 - a) gives Σ c of the additive samples, the flat beauty. Samples behind a
// transmittance below deep_min_transmittance are folded into the one in front first.
void to_over_form(std::vector<deep_sample>& samples);

// Whether sorted samples are non-overlapping: each one's front at or behind the previous one's
// back, and no two sharing a front depth.
bool deep_samples_tidy(const std::vector<deep_sample>& samples);

}  // namespace kiln
