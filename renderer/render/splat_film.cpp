#include "render/splat_film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/check.h"

namespace kiln {

pixel_splat::pixel_splat(int r, const bool (&layers)[matte_layer_count], int parts_per_sample)
    : reach(r),
      sum(size_t(2 * r + 1) * (2 * r + 1)),
      weight(sum.size()),
      part_count(parts_per_sample),
      parts(size_t(parts_per_sample) * sum.size()) {
  for (int l = 0; l < matte_layer_count; ++l)
    if (layers[l]) ids[l].resize(sum.size());
  clear();
}

void pixel_splat::clear() {
  std::fill(sum.begin(), sum.end(), dvec4(0.0));
  std::fill(weight.begin(), weight.end(), 0.0f);
  std::fill(parts.begin(), parts.end(), dvec3(0.0));
  for (std::vector<id_weights>& layer : ids)
    for (id_weights& w : layer) w.clear();
}

void pixel_splat::add(const reconstruction_filter& f, vec2 offset, const vec4& value,
                      const sample_mattes* mattes, const vec3* sample_parts) {
  constexpr int max_reach = 32;
  const int r = std::min(reach, max_reach);
  const int n = 2 * r + 1;
  // Separable kernel: one weight per column and per row. The distance to a pixel centre is the
  // in-pixel offset minus 0.5 minus a small integer, so box 0.5 keeps every sample in its own
  // pixel (offset - 0.5 ∈ [-0.5, 0.5)).
  float wx[2 * max_reach + 1], wy[2 * max_reach + 1];
  for (int k = -r; k <= r; ++k) {
    wx[k + r] = filter_weight_1d(f, (offset.x - 0.5f) - float(k));
    wy[k + r] = filter_weight_1d(f, (offset.y - 0.5f) - float(k));
  }
  for (int j = 0; j < n; ++j) {
    if (wy[j] == 0.0f) continue;
    for (int i = 0; i < n; ++i) {
      const float w = wx[i] * wy[j];
      if (w == 0.0f) continue;
      sum[size_t(j) * n + i] += dvec4(value) * double(w);
      weight[size_t(j) * n + i] += w;
      if (sample_parts)
        for (size_t c = 0; c < size_t(part_count); ++c)
          parts[size_t(part_count) * (size_t(j) * n + i) + c] += dvec3(sample_parts[c]) * double(w);
      if (!mattes) continue;
      for (int l = 0; l < matte_layer_count; ++l)
        if (!ids[l].empty())
          for (int k = 0; k < mattes->count; ++k)
            add_id_weight(ids[l][size_t(j) * n + i], mattes->ids[k][l], w * mattes->coverage[k]);
    }
  }
}

namespace {

// For each pixel along one axis, where its tile starts: start[i] = the low edge of the tile span
// holding i. Every tile's span along the axis must be one of a partition of [0, size).
std::vector<int> span_starts(const std::vector<pixel_rect>& tiles, int size, bool along_x) {
  std::vector<int> start(size_t(std::max(0, size)), -1);
  for (const pixel_rect& t : tiles) {
    const int lo = along_x ? t.x0 : t.y0, hi = along_x ? t.x1 : t.y1;
    KILN_CHECK(0 <= lo && lo < hi && hi <= size);
    for (int i = lo; i < hi; ++i) {
      KILN_CHECK(start[size_t(i)] == -1 || start[size_t(i)] == lo);  // spans overlap: not a grid
      start[size_t(i)] = lo;
    }
  }
  for (int s : start) KILN_CHECK(s >= 0);  // every pixel lies in some tile
  return start;
}

// The number of distinct spans in starts (columns or rows).
size_t span_count(const std::vector<int>& starts) {
  size_t n = 0;
  for (size_t i = 0; i < starts.size(); ++i) n += size_t(starts[i] == int(i));
  return n;
}

}  // namespace

splat_film::splat_film(int width, int height, const std::vector<pixel_rect>& tiles,
                       const reconstruction_filter& f, const bool (&layers)[matte_layer_count],
                       int part_count)
    : width_(width),
      height_(height),
      reach_(filter_reach(f)),
      window_((2 * reach_ + 1) * (2 * reach_ + 1)),
      column_start_(span_starts(tiles, width, true)),
      row_start_(span_starts(tiles, height, false)),
      parts_(part_count),
      // A filter that reaches no neighbour (box 0.5, the default) leaves no pixel on a tile
      // border: no slots, and no frame-sized index to zero.
      slot_of_(reach_ > 0 ? size_t(width) * height : 0, -1) {
  // One tile per column and row: the list is the grid, each cell once.
  KILN_CHECK(tiles.size() == span_count(column_start_) * span_count(row_start_));
  for (int l = 0; l < matte_layer_count; ++l) layers_[l] = layers[l];
  if (slot_of_.empty()) return;
  int64_t slots = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (!within_one_tile(x, y)) {
        slot_of_[size_t(y) * width + x] = slots;
        slots += window_;
      }
  slot_sum_.assign(size_t(slots), dvec4(0.0));
  slot_weight_.assign(size_t(slots), 0.0f);
  slot_parts_.assign(size_t(parts_) * size_t(slots), dvec3(0.0));
  for (int l = 0; l < matte_layer_count; ++l)
    if (layers[l]) slot_ids_[l].resize(size_t(slots));
}

// True when every pixel within reach of (x, y) (inside the image) belongs to (x, y)'s tile.
bool splat_film::within_one_tile(int x, int y) const {
  return column_start_[size_t(std::max(0, x - reach_))] ==
             column_start_[size_t(std::min(width_ - 1, x + reach_))] &&
         row_start_[size_t(std::max(0, y - reach_))] == row_start_[size_t(std::min(height_ - 1, y + reach_))];
}

void splat_film::begin_tile(tile_sums& t, const pixel_rect& tile) const {
  // A tile off the grid would let a source fold into a pixel outside t.
  KILN_CHECK(tile.x0 >= 0 && tile.y0 >= 0 && tile.x0 < tile.x1 && tile.y0 < tile.y1 && tile.x1 <= width_ &&
             tile.y1 <= height_ && column_start_[size_t(tile.x0)] == tile.x0 &&
             column_start_[size_t(tile.x1 - 1)] == tile.x0 &&
             (tile.x1 == width_ || column_start_[size_t(tile.x1)] == tile.x1) &&
             row_start_[size_t(tile.y0)] == tile.y0 && row_start_[size_t(tile.y1 - 1)] == tile.y0 &&
             (tile.y1 == height_ || row_start_[size_t(tile.y1)] == tile.y1));
  t.x0 = tile.x0;
  t.y0 = tile.y0;
  t.width = tile.width();
  t.height = tile.height();
  const size_t n = size_t(t.width) * t.height;
  t.sum.assign(n, dvec4(0.0));
  t.weight.assign(n, 0.0f);
  t.parts.assign(size_t(parts_) * n, dvec3(0.0));
  for (int l = 0; l < matte_layer_count; ++l) {
    t.ids[l].resize(layers_[l] ? n : 0);
    for (id_weights& w : t.ids[l]) w.clear();
  }
}

void splat_film::add(int x, int y, const pixel_splat& splat, tile_sums& t) {
  const int n = 2 * reach_ + 1;
  for (int j = -reach_; j <= reach_; ++j) {
    const int py = y + j;
    if (py < 0 || py >= height_) continue;
    for (int i = -reach_; i <= reach_; ++i) {
      const int px = x + i;
      if (px < 0 || px >= width_) continue;
      const size_t from = size_t(j + reach_) * n + size_t(i + reach_);
      const size_t p = size_t(py) * width_ + px;
      const int64_t slot = slot_of(p);
      if (slot < 0) {
        // (px, py)'s whole reach lies in one tile, which holds the source: this tile. The tile
        // renders its pixels in raster order, so this fold follows the source order.
        const size_t q = t.index(px, py);
        t.sum[q] += splat.sum[from];
        t.weight[q] += splat.weight[from];
        const size_t k = size_t(parts_);
        for (size_t c = 0; c < k; ++c) t.parts[k * q + c] += splat.parts[k * from + c];
        for (int l = 0; l < matte_layer_count; ++l)
          if (!t.ids[l].empty()) add_id_weights(t.ids[l][q], splat.ids[l][from]);
      } else {
        // The source sits at (-i, -j) from the destination; slots run in source raster order.
        const size_t to = size_t(slot) + size_t(reach_ - j) * n + size_t(reach_ - i);
        slot_sum_[to] = splat.sum[from];
        slot_weight_[to] = splat.weight[from];
        const size_t k = size_t(parts_);
        for (size_t c = 0; c < k; ++c) slot_parts_[k * to + c] = splat.parts[k * from + c];
        for (int l = 0; l < matte_layer_count; ++l)
          if (!slot_ids_[l].empty()) slot_ids_[l][to] = splat.ids[l][from];
      }
    }
  }
}

void store_beauty_parts(film& out, size_t p, const vec3* parts) {
  // A mean of values in [0, 1] can round just past 1 (Σ w·a in double over Σ w in float): the
  // albedo (a denoiser wants [0, 1]) and the mattes are clamped back (aov_row::clamp_unit).
  for (const aov_row& row : aov_table) {
    if (row.sampling != aov_sampling::filtered || row.shape == aov_shape::rgba || !out.aovs.has(row.id))
      continue;
    if (row.shape == aov_shape::triple) {
      out.vec3_layer(row.id)[p] = row.clamp_unit ? glm::clamp(*parts, 0.0f, 1.0f) : *parts;
      ++parts;
    } else if (row.shape == aov_shape::per_group) {
      const size_t groups = size_t(out.light_group_count());
      std::copy(parts, parts + groups, out.light_groups.begin() + p * groups);
      parts += groups;
    } else if (row.shape == aov_shape::per_matte) {
      const size_t mattes = size_t(out.shadow_count());
      for (size_t i = 0; i < mattes; ++i)
        out.shadow[p * mattes + i] = std::clamp(parts[i / 3][int(i % 3)], 0.0f, 1.0f);
      parts += shadow_part_count(out.light_group_count());
    }
  }
}

namespace {

// One pixel's folded sums, divided by its weight into the film.
void store_pixel(film& out, size_t p, const dvec4& sum, float weight, const dvec3* parts, int part_count,
                 const id_weights* const (&ids)[matte_layer_count]) {
  out.color[p] = weight > 0.0f ? vec4(sum / double(weight)) : vec4(0.0f);
  if (part_count > 0) {
    constexpr int stack_parts = 64;
    std::vector<vec3> heap(part_count > stack_parts ? size_t(part_count) : 0);
    vec3 stack[stack_parts];
    vec3* means = heap.empty() ? stack : heap.data();
    for (int c = 0; c < part_count; ++c)
      means[c] = weight > 0.0f ? vec3(parts[c] / double(weight)) : vec3(0.0f);
    store_beauty_parts(out, p, means);
  }
  std::vector<id_coverage>* ranks[matte_layer_count] = {&out.crypto_object, &out.crypto_material};
  const size_t depth = size_t(out.aovs.crypto_depth);
  for (int l = 0; l < matte_layer_count; ++l)
    if (ids[l] && !ranks[l]->empty()) store_ranks(*ids[l], weight, int(depth), ranks[l]->data() + p * depth);
}

}  // namespace

void splat_film::finish_tile(const tile_sums& t, film& out) const {
  for (int y = t.y0; y < t.y0 + t.height; ++y)
    for (int x = t.x0; x < t.x0 + t.width; ++x) {
      const size_t p = size_t(y) * width_ + x;
      if (slot_of(p) >= 0) continue;  // a border pixel: resolve() folds it
      const size_t q = t.index(x, y);
      const id_weights* ids[matte_layer_count] = {};
      for (int l = 0; l < matte_layer_count; ++l)
        if (!t.ids[l].empty()) ids[l] = &t.ids[l][q];
      store_pixel(out, p, t.sum[q], t.weight[q], t.parts.data() + size_t(parts_) * q, parts_, ids);
    }
}

void splat_film::resolve(film& out) const {
  // Border pixels in parallel: each is folded from its own slots alone, in slot (source) order.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, slot_of_.size(), 4096),
                    [&](const tbb::blocked_range<size_t>& rows) {
                      id_weights ids[matte_layer_count];
                      std::vector<dvec3> part_sums(static_cast<size_t>(parts_));
                      for (size_t p = rows.begin(); p < rows.end(); ++p) {
                        if (slot_of_[p] < 0) continue;
                        const size_t first = size_t(slot_of_[p]), end = first + size_t(window_);
                        dvec4 sum(0.0);
                        float weight = 0.0f;
                        for (size_t k = first; k < end; ++k) {
                          sum += slot_sum_[k];
                          weight += slot_weight_[k];
                        }
                        const size_t parts = part_sums.size();
                        for (size_t c = 0; c < parts; ++c) {
                          part_sums[c] = dvec3(0.0);
                          for (size_t k = first; k < end; ++k) part_sums[c] += slot_parts_[parts * k + c];
                        }
                        const id_weights* id_sums[matte_layer_count] = {};
                        for (int l = 0; l < matte_layer_count; ++l) {
                          if (slot_ids_[l].empty()) continue;
                          ids[l].clear();
                          for (size_t k = first; k < end; ++k) add_id_weights(ids[l], slot_ids_[l][k]);
                          id_sums[l] = &ids[l];
                        }
                        store_pixel(out, p, sum, weight, part_sums.data(), parts_, id_sums);
                      }
                    });
}

}  // namespace kiln
