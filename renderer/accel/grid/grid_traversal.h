// 3D-DDA traversal of a grid (Amanatides and Woo, "A Fast Voxel Traversal Algorithm", 1987),
// recursing into child nodes of the adaptive grid. Visits the cells a ray segment crosses in
// order and hands each leaf cell with its exit distance to a visitor, which says when to stop.
// All DDA arithmetic is in double: cell crossings are recomputed from the cell planes at each
// step (no accumulated increments), zero direction components never step (no inf·0), and the
// step count is bounded by the node's resolution, so traversal always terminates.
// Depends on grid.h only.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "accel/grid/grid.h"
#include "accel/grid/mailbox.h"

namespace kiln {

// A ray in double for traversal: the same parameter t as the float ray it came from.
struct dda_ray {
  dvec3 origin{0.0};
  dvec3 direction{0.0, 0.0, 1.0};
};

// The part [t0, t1] of the ray's extent inside box (slab test); false when it misses. Axes with
// a zero direction component are tested by the origin alone, never by dividing by zero.
inline bool clip_to_box(const dda_ray& r, const bounds3& box, double& t0, double& t1) {
  for (int a = 0; a < 3; ++a) {
    const double d = r.direction[a];
    if (d == 0.0) {
      if (r.origin[a] < box.lower[a] || r.origin[a] > box.upper[a]) return false;
      continue;
    }
    double near_t = (box.lower[a] - r.origin[a]) / d;
    double far_t = (box.upper[a] - r.origin[a]) / d;
    if (near_t > far_t) std::swap(near_t, far_t);
    t0 = std::max(t0, near_t);
    t1 = std::min(t1, far_t);
    if (t0 > t1) return false;
  }
  return true;
}

// Counts work for tests and benchmarks.
struct traversal_counters {
  uint64_t cells_visited = 0;
  uint64_t items_tested = 0;
};

// Calls f(item) for every item of the cell this query has not tested yet; returns true as soon
// as f does (an occlusion query's early exit), false otherwise.
template <typename function>
bool for_each_untested(const grid& g, const grid_cell& cell, mailbox& tested, function&& f) {
  for (uint32_t i = cell.first, end = cell.first + cell.count; i < end; ++i) {
    const uint32_t item = g.items[i];
    if (tested.first_visit(item) && f(item)) return true;
  }
  return false;
}

// Visits the leaf cells of node `node_index` crossed by the ray on [t0, t1], in order.
// visit(cell, t_cell_exit) returns true to stop (closest hit inside this cell, or any hit for
// occlusion). Returns true when the visitor stopped.
template <typename visitor>
bool traverse_grid(const grid& g, uint32_t node_index, const dda_ray& r, double t0, double t1, visitor& visit,
                   traversal_counters& counters) {
  const grid_node& node = g.nodes[node_index];
  if (!clip_to_box(r, node.box, t0, t1)) return false;

  // Entry cell from the entry point, clamped: an entry point on the box face maps inside.
  glm::ivec3 cell, step, stop;
  dvec3 next_t;
  const dvec3 entry = r.origin + t0 * r.direction;
  for (int a = 0; a < 3; ++a) {
    const double d = r.direction[a];
    int c = int(std::floor((entry[a] - node.box.lower[a]) / node.cell_size[a]));
    cell[a] = std::clamp(c, 0, node.resolution[a] - 1);
    if (d > 0.0) {
      step[a] = 1;
      stop[a] = node.resolution[a];
      next_t[a] = (node.box.lower[a] + (cell[a] + 1) * node.cell_size[a] - r.origin[a]) / d;
    } else if (d < 0.0) {
      step[a] = -1;
      stop[a] = -1;
      next_t[a] = (node.box.lower[a] + cell[a] * node.cell_size[a] - r.origin[a]) / d;
    } else {  // +0.0 or -0.0: never crosses a plane on this axis
      step[a] = 0;
      stop[a] = -2;
      next_t[a] = std::numeric_limits<double>::infinity();
    }
  }

  // Each step moves one axis one cell toward its far side, so sum(resolution) steps cross the node.
  const int max_steps = node.resolution.x + node.resolution.y + node.resolution.z;
  double t_enter = t0;
  for (int steps = 0; steps < max_steps; ++steps) {
    const int axis = next_t.x < next_t.y ? (next_t.x < next_t.z ? 0 : 2) : (next_t.y < next_t.z ? 1 : 2);
    const double t_exit = std::min(next_t[axis], t1);
    const grid_cell& c = g.cells[node.cell_index(cell)];
    ++counters.cells_visited;
    if (c.child >= 0) {
      if (traverse_grid(g, uint32_t(c.child), r, t_enter, t_exit, visit, counters)) return true;
      if (visit.done_within(t_exit)) return true;
    } else if (c.count > 0 && visit(c, t_exit)) {
      return true;
    }
    if (next_t[axis] >= t1) return false;  // the segment ends inside this cell
    cell[axis] += step[axis];
    if (cell[axis] == stop[axis]) return false;
    t_enter = next_t[axis];
    const int plane = step[axis] > 0 ? cell[axis] + 1 : cell[axis];
    next_t[axis] = (node.box.lower[axis] + plane * node.cell_size[axis] - r.origin[axis]) / r.direction[axis];
  }
  return false;
}

}  // namespace kiln
