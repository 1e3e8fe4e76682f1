#include "render/sample_pattern.h"

#include <gtest/gtest.h>

#include <set>

namespace kiln {
namespace {

TEST(sample_pattern, one_sample_is_the_pixel_centre) { EXPECT_EQ(sample_offset(3, 9, 0, 1), vec2(0.5f)); }

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

namespace kiln {
namespace {

TEST(sample_pattern, random_samples_are_uniform_unstratified_and_reproducible) {
  // Reproducible: a function of (pixel, sample) only.
  EXPECT_EQ(random_sample_offset(7, 3, 5), random_sample_offset(7, 3, 5));
  EXPECT_NE(random_sample_offset(7, 3, 5), random_sample_offset(7, 3, 6));
  // Uniform over the pixel: the mean of many samples is the centre, the quadrants fill evenly.
  const int n = 4096;
  vec2 sum(0.0f);
  int quadrant[4] = {0, 0, 0, 0};
  for (int s = 0; s < n; ++s) {
    vec2 o = random_sample_offset(11, 19, uint32_t(s));
    ASSERT_GE(o.x, 0.0f);
    ASSERT_LT(o.x, 1.0f);
    ASSERT_GE(o.y, 0.0f);
    ASSERT_LT(o.y, 1.0f);
    sum += o;
    ++quadrant[(o.x >= 0.5f) + 2 * (o.y >= 0.5f)];
  }
  EXPECT_NEAR(sum.x / n, 0.5f, 0.02f);
  EXPECT_NEAR(sum.y / n, 0.5f, 0.02f);
  for (int q : quadrant) EXPECT_NEAR(q, n / 4, n / 16);
  // Not stratified: with 4 samples, some pixel puts two in one quadrant (strata never do).
  bool clumped = false;
  for (uint32_t px = 0; px < 64 && !clumped; ++px) {
    int seen[4] = {0, 0, 0, 0};
    for (uint32_t s = 0; s < 4; ++s) {
      vec2 o = random_sample_offset(px, 0, s);
      if (++seen[(o.x >= 0.5f) + 2 * (o.y >= 0.5f)] > 1) clumped = true;
    }
  }
  EXPECT_TRUE(clumped);
}

}  // namespace
}  // namespace kiln
