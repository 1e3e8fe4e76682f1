#include "render/id_coverage.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

TEST(id_coverage, ranks_sort_by_coverage_then_id_and_pad_with_zeros) {
  id_weights sums;
  add_id_weight(sums, 7, 0.25f);
  add_id_weight(sums, 3, 0.5f);
  add_id_weight(sums, 9, 0.25f);
  add_id_weight(sums, 7, 0.5f);  // 7 now holds 0.75
  id_coverage ranks[5];
  store_ranks(sums, 2.0f, 5, ranks);
  EXPECT_EQ(ranks[0], (id_coverage{7, 0.375f}));
  EXPECT_EQ(ranks[1], (id_coverage{3, 0.25f}));
  EXPECT_EQ(ranks[2], (id_coverage{9, 0.125f}));
  EXPECT_EQ(ranks[3], id_coverage{});
  EXPECT_EQ(ranks[4], id_coverage{});
  // Equal coverage: the smaller id first, whichever was met first.
  id_weights tied = {{9, 1.0f}, {4, 1.0f}};
  store_ranks(tied, 2.0f, 2, ranks);
  EXPECT_EQ(ranks[0].id, 4u);
  EXPECT_EQ(ranks[1].id, 9u);
  // Fewer ranks than ids: the smallest coverages are dropped.
  store_ranks(sums, 1.0f, 1, ranks);
  EXPECT_EQ(ranks[0], (id_coverage{7, 0.75f}));
  // No weight at all (nothing within the filter's reach): nothing is covered.
  store_ranks(sums, 0.0f, 2, ranks);
  EXPECT_EQ(ranks[0], id_coverage{});
}

TEST(id_coverage, merging_adds_per_id) {
  id_weights into = {{1, 0.5f}};
  add_id_weights(into, {{2, 0.25f}, {1, 0.125f}});
  ASSERT_EQ(into.size(), 2u);
  EXPECT_EQ(into[0].id, 1u);
  EXPECT_EQ(into[0].weight, 0.625f);
  EXPECT_EQ(into[1].id, 2u);
  EXPECT_EQ(into[1].weight, 0.25f);
}

TEST(id_coverage, table_lookup_falls_back_to_the_key) {
  const std::vector<uint32_t> table = {100, 200};
  EXPECT_EQ(matte_id(table, 1), 200u);
  EXPECT_EQ(matte_id(table, 5), 5u);
}

}  // namespace
}  // namespace kiln
