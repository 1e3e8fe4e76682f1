#include "render/splat_film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace kiln {

pixel_splat::pixel_splat(int r, const bool (&layers)[matte_layer_count], bool with_split)
    : reach(r),
      sum(size_t(2 * r + 1) * (2 * r + 1)),
      weight(sum.size()),
      split(with_split ? 3 * sum.size() : 0) {
  for (int l = 0; l < matte_layer_count; ++l)
    if (layers[l]) ids[l].resize(sum.size());
  clear();
}

void pixel_splat::clear() {
  std::fill(sum.begin(), sum.end(), dvec4(0.0));
  std::fill(weight.begin(), weight.end(), 0.0f);
  std::fill(split.begin(), split.end(), dvec3(0.0));
  for (std::vector<id_weights>& layer : ids)
    for (id_weights& w : layer) w.clear();
}

void pixel_splat::add(const reconstruction_filter& f, vec2 offset, const vec4& value,
                      const uint32_t* sample_ids, const vec3* sample_split) {
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
      if (!split.empty() && sample_split)
        for (size_t c = 0; c < 3; ++c)
          split[3 * (size_t(j) * n + i) + c] += dvec3(sample_split[c]) * double(w);
      if (!sample_ids) continue;
      for (int l = 0; l < matte_layer_count; ++l)
        if (!ids[l].empty()) add_id_weight(ids[l][size_t(j) * n + i], sample_ids[l], w);
    }
  }
}

splat_film::splat_film(int width, int height, int tile_size, const reconstruction_filter& f,
                       const bool (&layers)[matte_layer_count], bool with_split)
    : width_(width),
      height_(height),
      tile_size_(std::max(1, tile_size)),
      reach_(filter_reach(f)),
      window_((2 * reach_ + 1) * (2 * reach_ + 1)),
      sum_(size_t(width) * height, dvec4(0.0)),
      weight_(size_t(width) * height, 0.0f),
      slot_of_(size_t(width) * height, -1) {
  int64_t slots = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (!within_one_tile(x, y)) {
        slot_of_[size_t(y) * width + x] = slots;
        slots += window_;
      }
  slot_sum_.assign(size_t(slots), dvec4(0.0));
  slot_weight_.assign(size_t(slots), 0.0f);
  if (with_split) {
    split_sum_.assign(3 * sum_.size(), dvec3(0.0));
    slot_split_.assign(3 * size_t(slots), dvec3(0.0));
  }
  for (int l = 0; l < matte_layer_count; ++l)
    if (layers[l]) {
      id_sum_[l].resize(sum_.size());
      slot_ids_[l].resize(size_t(slots));
    }
}

// True when every pixel within reach of (x, y) (inside the image) belongs to (x, y)'s tile.
bool splat_film::within_one_tile(int x, int y) const {
  auto same = [this](int a, int b) { return a / tile_size_ == b / tile_size_; };
  return same(std::max(0, x - reach_), std::min(width_ - 1, x + reach_)) &&
         same(std::max(0, y - reach_), std::min(height_ - 1, y + reach_));
}

void splat_film::add(int x, int y, const pixel_splat& splat) {
  const int n = 2 * reach_ + 1;
  for (int j = -reach_; j <= reach_; ++j) {
    const int py = y + j;
    if (py < 0 || py >= height_) continue;
    for (int i = -reach_; i <= reach_; ++i) {
      const int px = x + i;
      if (px < 0 || px >= width_) continue;
      const size_t from = size_t(j + reach_) * n + size_t(i + reach_);
      const size_t p = size_t(py) * width_ + px;
      const int64_t slot = slot_of_[p];
      if (slot < 0) {
        // The tile renders its pixels in raster order, so this fold follows the source order.
        sum_[p] += splat.sum[from];
        weight_[p] += splat.weight[from];
        if (!split_sum_.empty())
          for (size_t c = 0; c < 3; ++c) split_sum_[3 * p + c] += splat.split[3 * from + c];
        for (int l = 0; l < matte_layer_count; ++l)
          if (!id_sum_[l].empty()) add_id_weights(id_sum_[l][p], splat.ids[l][from]);
      } else {
        // The source sits at (-i, -j) from the destination; slots run in source raster order.
        const size_t to = size_t(slot) + size_t(reach_ - j) * n + size_t(reach_ - i);
        slot_sum_[to] = splat.sum[from];
        slot_weight_[to] = splat.weight[from];
        if (!slot_split_.empty())
          for (size_t c = 0; c < 3; ++c) slot_split_[3 * to + c] = splat.split[3 * from + c];
        for (int l = 0; l < matte_layer_count; ++l)
          if (!slot_ids_[l].empty()) slot_ids_[l][to] = splat.ids[l][from];
      }
    }
  }
}

void splat_film::resolve(film& out) const {
  std::vector<id_coverage>* ranks[matte_layer_count] = {&out.crypto_object, &out.crypto_material};
  const size_t depth = size_t(out.aovs.crypto_depth);
  // Rows in parallel: every pixel is resolved from its own sums alone.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, sum_.size(), 4096), [&](const tbb::blocked_range<size_t>& rows) {
  id_weights ids;
  for (size_t p = rows.begin(); p < rows.end(); ++p) {
    dvec4 sum = sum_[p];
    float weight = weight_[p];
    if (slot_of_[p] >= 0)
      for (size_t k = size_t(slot_of_[p]), end = k + size_t(window_); k < end; ++k) {
        sum += slot_sum_[k];
        weight += slot_weight_[k];
      }
    out.color[p] = weight > 0.0f ? vec4(sum / double(weight)) : vec4(0.0f);
    if (!split_sum_.empty()) {
      std::vector<vec3>* parts[3] = {&out.direct, &out.reflection, &out.refraction};
      for (size_t c = 0; c < 3; ++c) {
        dvec3 part = split_sum_[3 * p + c];
        if (slot_of_[p] >= 0)
          for (size_t k = size_t(slot_of_[p]), end = k + size_t(window_); k < end; ++k)
            part += slot_split_[3 * k + c];
        if (!parts[c]->empty()) (*parts[c])[p] = weight > 0.0f ? vec3(part / double(weight)) : vec3(0.0f);
      }
    }
    for (int l = 0; l < matte_layer_count; ++l) {
      if (id_sum_[l].empty() || ranks[l]->empty()) continue;
      ids = id_sum_[l][p];
      if (slot_of_[p] >= 0)
        for (size_t k = size_t(slot_of_[p]), end = k + size_t(window_); k < end; ++k)
          add_id_weights(ids, slot_ids_[l][k]);
      store_ranks(ids, weight, int(depth), ranks[l]->data() + p * depth);
    }
  }
  });
}

}  // namespace kiln
