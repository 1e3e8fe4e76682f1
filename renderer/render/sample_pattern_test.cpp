#include "render/sample_pattern.h"

#include <gtest/gtest.h>

#include <set>

namespace kiln {
namespace {

TEST(sample_pattern, one_sample_is_the_pixel_centre) {
  EXPECT_EQ(sample_offset(3, 9, 0, 1), vec2(0.5f));
}

TEST(sample_pattern, samples_depend_only_on_pixel_and_index) {
  EXPECT_EQ(sample_offset(5, 6, 3, 16), sample_offset(5, 6, 3, 16));
  EXPECT_NE(sample_offset(5, 6, 3, 16), sample_offset(6, 5, 3, 16));
}

TEST(sample_pattern, samples_are_stratified_one_per_cell) {
  for (uint32_t spp : {4u, 9u, 16u, 6u}) {
    uint32_t columns = 1;
    while (columns * columns < spp) ++columns;
    uint32_t rows = (spp + columns - 1) / columns;
    std::set<std::pair<int, int>> cells;
    for (uint32_t s = 0; s < spp; ++s) {
      vec2 o = sample_offset(11, 17, s, spp);
      ASSERT_GE(o.x, 0.0f);
      ASSERT_LT(o.x, 1.0f);
      ASSERT_GE(o.y, 0.0f);
      ASSERT_LT(o.y, 1.0f);
      cells.insert({int(o.x * columns), int(o.y * rows)});
    }
    EXPECT_EQ(cells.size(), spp);
  }
}

}  // namespace
}  // namespace kiln
