#include "render/id_coverage.h"

#include <algorithm>

namespace kiln {

uint32_t matte_id(const std::vector<uint32_t>& table, int32_t key) {
  return key >= 0 && size_t(key) < table.size() ? table[size_t(key)] : uint32_t(key);
}

void add_id_weight(id_weights& sums, uint32_t id, float w) {
  for (id_weight& e : sums)
    if (e.id == id) {
      e.weight += w;
      return;
    }
  sums.push_back({id, w});
}

void add_id_weights(id_weights& into, const id_weights& from) {
  for (const id_weight& e : from) add_id_weight(into, e.id, e.weight);
}

void store_ranks(const id_weights& sums, float total, int depth, id_coverage* ranks) {
  id_weights sorted = sums;
  std::sort(sorted.begin(), sorted.end(), [](const id_weight& a, const id_weight& b) {
    return a.weight != b.weight ? a.weight > b.weight : a.id < b.id;
  });
  for (int k = 0; k < depth; ++k)
    ranks[k] = size_t(k) < sorted.size() && total > 0.0f && sorted[size_t(k)].weight > 0.0f
                   ? id_coverage{sorted[size_t(k)].id, sorted[size_t(k)].weight / total}
                   : id_coverage{};
}

}  // namespace kiln
