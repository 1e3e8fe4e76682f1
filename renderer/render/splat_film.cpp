#include "render/splat_film.h"

#include <algorithm>
#include <utility>

namespace kiln {

splat_tile make_splat_tile(int x0, int y0, int x1, int y1, int reach) {
  splat_tile t;
  t.x0 = x0 - reach;
  t.y0 = y0 - reach;
  t.width = x1 - x0 + 2 * reach;
  t.height = y1 - y0 + 2 * reach;
  t.sum.assign(size_t(t.width) * t.height, vec4(0.0f));
  t.weight.assign(size_t(t.width) * t.height, 0.0f);
  return t;
}

void splat_sample(splat_tile& t, const reconstruction_filter& f, int px, int py, vec2 offset,
                  const vec4& value) {
  constexpr int max_reach = 32;
  const int reach = std::min(filter_reach(f), max_reach);
  // Separable kernel: one weight per column and per row. Offsets from pixel centres are formed
  // from the small integer distance and the in-pixel offset, so box 0.5 puts every sample in its
  // own pixel only (offset - 0.5 ∈ [-0.5, 0.5)).
  float wx[2 * max_reach + 1], wy[2 * max_reach + 1];
  for (int k = -reach; k <= reach; ++k) {
    wx[k + reach] = filter_weight_1d(f, (offset.x - 0.5f) - float(k));
    wy[k + reach] = filter_weight_1d(f, (offset.y - 0.5f) - float(k));
  }
  for (int j = -reach; j <= reach; ++j) {
    if (wy[j + reach] == 0.0f) continue;
    const int by = py + j - t.y0;
    for (int i = -reach; i <= reach; ++i) {
      const float w = wx[i + reach] * wy[j + reach];
      if (w == 0.0f) continue;
      const size_t b = size_t(by) * t.width + size_t(px + i - t.x0);
      t.sum[b] += value * w;
      t.weight[b] += w;
    }
  }
}

ordered_tile_merge::ordered_tile_merge(int width, int height, size_t tile_count)
    : width_(width),
      height_(height),
      sum_(size_t(width) * height, vec4(0.0f)),
      weight_(size_t(width) * height, 0.0f),
      waiting_(tile_count),
      arrived_(tile_count, false) {}

void ordered_tile_merge::add(size_t index, splat_tile tile) {
  waiting_[index] = std::move(tile);
  arrived_[index] = true;
  while (next_ < waiting_.size() && arrived_[next_]) {
    merge(waiting_[next_]);
    waiting_[next_] = splat_tile{};
    ++next_;
  }
}

void ordered_tile_merge::merge(const splat_tile& t) {
  for (int y = std::max(0, t.y0); y < std::min(height_, t.y0 + t.height); ++y)
    for (int x = std::max(0, t.x0); x < std::min(width_, t.x0 + t.width); ++x) {
      const size_t b = size_t(y - t.y0) * t.width + size_t(x - t.x0);
      const size_t i = size_t(y) * width_ + x;
      sum_[i] += t.sum[b];
      weight_[i] += t.weight[b];
    }
}

void ordered_tile_merge::resolve(film& out) const {
  for (size_t i = 0; i < sum_.size(); ++i)
    out.color[i] = weight_[i] > 0.0f ? sum_[i] / weight_[i] : vec4(0.0f);
}

}  // namespace kiln
