#include "accel/grid/triangle_box.h"

#include <gtest/gtest.h>

#include <random>

namespace kiln {
namespace {

const bounds3 unit_box{dvec3(0.0), dvec3(1.0)};

TEST(triangle_box, simple_cases) {
  // Inside, straddling a face, far away.
  EXPECT_TRUE(triangle_box_overlap({0.2, 0.2, 0.5}, {0.8, 0.2, 0.5}, {0.5, 0.8, 0.5}, unit_box));
  EXPECT_TRUE(triangle_box_overlap({-1, 0.5, 0.5}, {2, 0.4, 0.5}, {0.5, 0.6, 3}, unit_box));
  EXPECT_FALSE(triangle_box_overlap({2, 2, 2}, {3, 2, 2}, {2, 3, 2}, unit_box));
  // A large triangle whose plane cuts past the box: bounds overlap, plane separates.
  EXPECT_FALSE(triangle_box_overlap({3, 0, 0}, {0, 3, 0}, {0, 0, 3.5}, bounds3{dvec3(0.0), dvec3(0.5)}));
  EXPECT_TRUE(triangle_box_overlap({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, bounds3{dvec3(0.0), dvec3(0.5)}));
  // Touching a face or a corner counts.
  EXPECT_TRUE(triangle_box_overlap({1, 0.5, 0.5}, {2, 0.5, 0.5}, {2, 0.6, 0.5}, unit_box));
  EXPECT_TRUE(triangle_box_overlap({1, 1, 1}, {2, 1, 1}, {1, 2, 1}, unit_box));
}

TEST(triangle_box, plane_separates_a_triangle_beside_the_corner) {
  // The triangle's plane x + y = 2.2 passes the box edge (1, 1, z) by 0.2: its bounds overlap the
  // box, so only the SAT axes tell it apart from the one at x + y = 1.8 that cuts the box.
  EXPECT_FALSE(triangle_box_overlap({2.2, 0.0, -1.0}, {0.0, 2.2, -1.0}, {1.1, 1.1, 3.0}, unit_box));
  EXPECT_TRUE(triangle_box_overlap({1.8, 0.0, -1.0}, {0.0, 1.8, -1.0}, {0.9, 0.9, 3.0}, unit_box));
}

// Against sampling: a triangle with a sample point inside the box must overlap, and a triangle
// reported as overlapping must come close to the box (within the sampling resolution).
TEST(triangle_box, agrees_with_dense_sampling) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  int overlapping = 0, separated = 0;
  for (int i = 0; i < 3000; ++i) {
    dvec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng)), p2(u(rng), u(rng), u(rng));
    const bool overlap = triangle_box_overlap(p0, p1, p2, unit_box);
    double nearest = 1e9;
    bool sampled_inside = false;
    const int n = 60;
    for (int a = 0; a <= n; ++a)
      for (int b = 0; a + b <= n; ++b) {
        dvec3 q = p0 + (double(a) / n) * (p1 - p0) + (double(b) / n) * (p2 - p0);
        dvec3 outside = glm::max(glm::max(unit_box.lower - q, q - unit_box.upper), dvec3(0.0));
        double dist = glm::length(outside);
        nearest = std::min(nearest, dist);
        if (dist == 0.0) sampled_inside = true;
      }
    if (sampled_inside) {
      EXPECT_TRUE(overlap) << i;
    }
    const double spacing = std::max({glm::length(p1 - p0), glm::length(p2 - p0), glm::length(p2 - p1)}) / n;
    if (overlap) {
      EXPECT_LE(nearest, spacing) << i;
    }
    (overlap ? overlapping : separated)++;
  }
  EXPECT_GT(overlapping, 300);
  EXPECT_GT(separated, 300);
}

}  // namespace
}  // namespace kiln
