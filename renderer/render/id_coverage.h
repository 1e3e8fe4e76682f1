// Cryptomatte's ranking filter (Friedman and Jones 2015, "Fully automatic ID mattes with support
// for motion blur and transparency"): per pixel, the filter weight of the samples that hit each id
// is summed, divided by the pixel's total weight, and the ids ranked by that coverage. Depends on
// core and render only; the ids themselves (hashes of names) come from the caller.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film.h"

namespace kiln {

// The two Cryptomatte layers kiln writes, as indices into per-layer arrays.
enum matte_layer : int { object_layer = 0, material_layer = 1, matte_layer_count = 2 };

// The ids one sample covers in each layer, with the share of the sample each covers (1 for an
// opaque hit; through BLEND surfaces several, summing to the sample's alpha).
constexpr int max_sample_mattes = 8;
struct sample_mattes {
  uint32_t ids[max_sample_mattes][matte_layer_count] = {};
  float coverage[max_sample_mattes] = {};
  int count = 0;  // 0: the sample hit nothing
};

// Summed filter weight of the samples that hit one id.
struct id_weight {
  uint32_t id = 0;
  float weight = 0.0f;
};

// A pixel's (or one source's share of a pixel's) weights per id, in first-seen order. Few ids reach
// one pixel, so a linear search beats a map.
using id_weights = std::vector<id_weight>;

// The id of each sample's object and material: the caller's table entry for the glTF node and the
// material's source index (a key beyond a table is its own id, for scenes built without names).
struct matte_ids {
  std::vector<uint32_t> object_by_node;
  std::vector<uint32_t> material_by_source;
};

uint32_t matte_id(const std::vector<uint32_t>& table, int32_t key);

// sums[id] += w.
void add_id_weight(id_weights& sums, uint32_t id, float w);

// into[id] += from[id] for every id of from, so folding sources in one order gives one result
// whatever order the ids were first seen in.
void add_id_weights(id_weights& into, const id_weights& from);

// Writes depth ranks: coverage = weight / total, sorted descending (equal coverage: smaller id
// first, so the order never depends on how the ids were met); unused ranks are {0, 0}.
void store_ranks(const id_weights& sums, float total, int depth, id_coverage* ranks);

}  // namespace kiln
