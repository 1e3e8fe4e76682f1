// The grid data structure shared by the uniform and the adaptive grid: nodes (a box split into
// res.x·res.y·res.z cells), cells (a run of item ids, or a child node covering the cell) and
// one flat item-id array. Items are opaque ids (triangles of one mesh, or instances): the
// builder sees them only through their bounds and an overlap predicate.
// Depends on core only; knows nothing of meshes, instances or Embree.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/math.h"

namespace kiln {

// How a grid is sized and subdivided.
//
// Resolution heuristic (Cleary and Wyvill; Pharr and Humphreys' GridAccel): aim for
// cells ≈ density·N for N items, with cubic cells, so the cell side is cbrt(volume / (density·N))
// and each axis gets ceil(extent / side) cells, capped at max_resolution. density = 2 keeps the
// cells a little smaller than the average item. `resolution` overrides the heuristic.
struct grid_options {
  double density = 2.0;
  int max_resolution = 256;
  std::optional<glm::ivec3> resolution;
  // Adaptive grid: a cell holding more than max_items_per_cell items is split into
  // child_resolution³ cells (octree-like for 2), recursively, at most max_depth levels deep.
  // max_depth = 0 is the uniform grid.
  int max_items_per_cell = 8;
  int max_depth = 0;
  int child_resolution = 2;
};

// The default options of the uniform and the adaptive grid.
grid_options uniform_grid_options();
grid_options adaptive_grid_options();

// Sizes of a built structure (one grid, or all the grids of a scene), for benchmarks and
// `kiln compare`'s report.
struct grid_statistics {
  size_t nodes = 0;
  size_t cells = 0;
  size_t item_references = 0;
  size_t memory_bytes = 0;
};

struct grid_cell {
  uint32_t first = 0;  // index of the cell's first item id in grid.items
  uint32_t count = 0;  // items in this cell (0 when it has a child)
  int32_t child = -1;  // node that subdivides this cell, or -1
};

struct grid_node {
  bounds3 box;
  glm::ivec3 resolution{1};
  dvec3 cell_size{1.0};
  uint32_t first_cell = 0;  // cells of this node, x fastest, in grid.cells

  uint32_t cell_index(const glm::ivec3& c) const {
    return first_cell + uint32_t((c.z * resolution.y + c.y) * resolution.x + c.x);
  }
};

struct grid {
  std::vector<grid_node> nodes;  // nodes[0] is the root; empty for a grid without items
  std::vector<grid_cell> cells;
  std::vector<uint32_t> items;

  bool empty() const { return nodes.empty(); }
  size_t memory_bytes() const {
    return nodes.capacity() * sizeof(grid_node) + cells.capacity() * sizeof(grid_cell) +
           items.capacity() * sizeof(uint32_t);
  }
};

// Bounds of item i (empty bounds: the item is left out, e.g. an empty mesh).
using item_bounds_function = std::function<bounds3(uint32_t)>;
// Whether item i touches the (already padded) box; may be exact (triangles) or bounds-only.
using item_overlap_function = std::function<bool(uint32_t, const bounds3&)>;

// Builds a grid over item_count items. Each item goes into every cell it overlaps; cells are
// padded by a small margin before the overlap test, so an item touching a cell face is in both
// neighbours and traversal can never skip it because of rounding.
grid build_grid(uint32_t item_count, const item_bounds_function& item_bounds,
                const item_overlap_function& overlaps, const grid_options& options);

// The grid resolution the heuristic picks for item_count items in box (exposed for tests).
glm::ivec3 grid_resolution(const bounds3& box, size_t item_count, const grid_options& options);

}  // namespace kiln
