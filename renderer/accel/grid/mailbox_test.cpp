// Mailboxing: an item referenced by many cells along a ray is tested once per ray, and a collision
// in the per-query cache can cost a repeated test, never a skipped one.
#include "accel/grid/mailbox.h"

#include <gtest/gtest.h>

#include "accel/grid/mesh_grid.h"

namespace kiln {
namespace {

// One large triangle in the plane z = y, spanning x + y <= 1, in an 8³ grid over its bounds.
mesh large_triangle() {
  mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
  m.indices = {0, 1, 2};
  m.bounds = bounds3{dvec3(0.0), dvec3(1.0)};
  return m;
}

mesh_grid fine_grid(const mesh& m) {
  grid_options o = uniform_grid_options();
  o.resolution = glm::ivec3(8);
  return build_mesh_grid(m, o);
}

TEST(mailbox, triangle_spanning_many_cells_is_tested_once_by_a_ray_that_misses_it) {
  const mesh m = large_triangle();
  const mesh_grid g = fine_grid(m);
  ASSERT_GT(g.cells.items.size(), 20u) << "the triangle is referenced by many cells";
  // Along +x at y = 0.3, z = 0.31: parallel to the triangle's plane, 0.01 above it, through the
  // row of cells it fills for x in [0, 0.7] (it touches every cell of that row up to x = 0.75).
  shape_hit best;
  traversal_counters counters;
  EXPECT_FALSE(
      intersect_mesh_grid(g, m, {-0.5f, 0.3f, 0.31f}, {1.0f, 0.0f, 0.0f}, 0.0f, inf, best, counters));
  EXPECT_EQ(counters.cells_visited, 8u);
  EXPECT_EQ(counters.items_tested, 1u);
  traversal_counters occlusion;
  EXPECT_FALSE(occluded_mesh_grid(g, m, {-0.5f, 0.3f, 0.31f}, {1.0f, 0.0f, 0.0f}, 0.0f, inf, occlusion));
  EXPECT_EQ(occlusion.items_tested, 1u);
}

TEST(mailbox, triangle_hit_at_the_far_end_of_a_long_grazing_path_is_tested_once) {
  const mesh m = large_triangle();
  const mesh_grid g = fine_grid(m);
  // From (0.1, 0, 0.05), closing on the plane z = y at a tenth of the rate it runs along it: the
  // hit is at (0.1, 0.5, 0.5), four cells up, and the cells on the way, all within 0.05 of the
  // plane, hold the triangle too.
  const vec3 origin(0.1f, 0.0f, 0.05f), direction = glm::normalize(vec3(0.0f, 1.0f, 0.9f));
  shape_hit best;
  traversal_counters counters;
  ASSERT_TRUE(intersect_mesh_grid(g, m, origin, direction, 0.0f, inf, best, counters));
  const vec3 p = origin + best.t * direction;
  EXPECT_NEAR(p.y, 0.5f, 1e-5f);
  EXPECT_NEAR(p.z, 0.5f, 1e-5f);
  EXPECT_NEAR(best.u, 0.1f, 1e-5f);  // p = u·(1,0,0) + v·(0,1,1)
  EXPECT_NEAR(best.v, 0.5f, 1e-5f);
  EXPECT_GE(counters.cells_visited, 4u);
  EXPECT_EQ(counters.items_tested, 1u);
}

TEST(mailbox, collisions_repeat_a_test_but_never_skip_one) {
  mailbox tested;
  EXPECT_TRUE(tested.first_visit(5));
  EXPECT_FALSE(tested.first_visit(5));
  EXPECT_TRUE(tested.first_visit(6));
  EXPECT_TRUE(tested.first_visit(5 + 64));  // same slot as 5: evicts it
  EXPECT_FALSE(tested.first_visit(5 + 64));
  EXPECT_TRUE(tested.first_visit(5));  // tested again, not skipped
  EXPECT_FALSE(tested.first_visit(6));
}

}  // namespace
}  // namespace kiln
