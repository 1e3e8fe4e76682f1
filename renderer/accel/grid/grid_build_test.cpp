// The adaptive grid's two limits: a cell with more than max_items_per_cell items is split while
// depth allows, and no leaf ever lies deeper than max_depth, even where no split can separate the
// items (coincident triangles).
#include <gtest/gtest.h>

#include "accel/grid/mesh_grid.h"
#include "accel/grid/synthetic_scenes.h"

namespace kiln {
namespace {

struct leaf_census {
  int deepest = 0;                 // depth of the deepest leaf cell (root cells are depth 0)
  size_t crowded_above_limit = 0;  // leaves shallower than max_depth holding more than n items
  size_t crowded_at_limit = 0;     // leaves at max_depth holding more than n items
  size_t leaves = 0;
};

void walk(const grid& g, uint32_t node_index, int depth, const grid_options& o, leaf_census& census) {
  const grid_node& node = g.nodes[node_index];
  const size_t cell_count = size_t(node.resolution.x) * node.resolution.y * node.resolution.z;
  for (size_t i = 0; i < cell_count; ++i) {
    const grid_cell& c = g.cells[node.first_cell + i];
    if (c.child >= 0) {
      EXPECT_EQ(c.count, 0u);
      EXPECT_EQ(g.nodes[size_t(c.child)].resolution, glm::ivec3(o.child_resolution));
      walk(g, uint32_t(c.child), depth + 1, o, census);
      continue;
    }
    ++census.leaves;
    census.deepest = std::max(census.deepest, depth);
    if (c.count > uint32_t(o.max_items_per_cell))
      ++(depth < o.max_depth ? census.crowded_above_limit : census.crowded_at_limit);
  }
}

// A sparse soup plus 40 copies of one small triangle: the copies crowd every cell they touch at
// every depth.
mesh crowded_mesh() {
  mesh m = make_triangle_soup(3000, 11, 1.0f, 0.05f);
  for (int copy = 0; copy < 40; ++copy) {
    const uint32_t base = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {{0.3f, 0.3f, 0.3f}, {0.31f, 0.3f, 0.3f}, {0.3f, 0.31f, 0.3f}});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  }
  m.bounds = bounds3{};
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  return m;
}

TEST(grid_build, adaptive_grid_never_exceeds_max_depth_and_splits_crowded_cells) {
  const mesh m = crowded_mesh();
  size_t previous_nodes = 0;
  for (int max_items : {4, 8}) {
    for (int max_depth = 0; max_depth <= 4; ++max_depth) {
      grid_options o = adaptive_grid_options();
      o.max_items_per_cell = max_items;
      o.max_depth = max_depth;
      const mesh_grid g = build_mesh_grid(m, o);
      leaf_census census;
      walk(g.cells, 0, 0, o, census);
      SCOPED_TRACE("n = " + std::to_string(max_items) + ", d = " + std::to_string(max_depth));
      EXPECT_LE(census.deepest, max_depth);
      EXPECT_EQ(census.crowded_above_limit, 0u) << "a cell over n items was left unsplit";
      // The coincident copies cannot be separated: they reach the depth limit and stay crowded.
      EXPECT_EQ(census.deepest, max_depth);
      EXPECT_GT(census.crowded_at_limit, 0u);
      if (max_depth == 0) {
        EXPECT_EQ(g.cells.nodes.size(), 1u);
      } else {
        EXPECT_GT(g.cells.nodes.size(), previous_nodes);
      }
      previous_nodes = g.cells.nodes.size();
    }
    previous_nodes = 0;
  }
}

TEST(grid_build, adaptive_grid_does_not_split_cells_within_the_item_limit) {
  const mesh m = crowded_mesh();
  grid_options o = adaptive_grid_options();
  o.max_items_per_cell = 100;  // more than any cell holds: the 40 copies and a few soup triangles
  const mesh_grid g = build_mesh_grid(m, o);
  size_t largest = 0;
  for (const grid_cell& c : g.cells.cells) largest = std::max<size_t>(largest, c.count);
  EXPECT_LE(largest, 100u);
  EXPECT_GE(largest, 40u);
  EXPECT_EQ(g.cells.nodes.size(), 1u);
}

}  // namespace
}  // namespace kiln
