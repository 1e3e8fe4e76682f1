#include <algorithm>
#include <cmath>

#include "accel/grid/grid.h"
#include "core/check.h"

namespace kiln {

namespace {

// Relative padding of the root box and of every cell before the overlap test. It is far above
// double rounding of the DDA's plane crossings and far below any cell size worth building.
constexpr double box_padding = 1e-6;
constexpr double cell_padding = 1e-5;

// A box with no zero-width axis (flat meshes, axis-aligned quads), padded so that items on its
// faces lie strictly inside.
bounds3 padded_root(const bounds3& b) {
  dvec3 extent = b.diagonal();
  double largest = std::max({extent.x, extent.y, extent.z, glm::length(b.center()) * 1e-6, 1e-30});
  dvec3 pad = dvec3(largest * box_padding) + extent * box_padding;
  return bounds3{b.lower - pad, b.upper + pad};
}

bounds3 cell_box(const grid_node& n, const glm::ivec3& c) {
  dvec3 lower = n.box.lower + dvec3(c) * n.cell_size;
  dvec3 pad = n.cell_size * cell_padding;
  return bounds3{lower - pad, lower + n.cell_size + pad};
}

// Range of cells a box covers, clamped to the node.
void cell_range(const grid_node& n, const bounds3& b, glm::ivec3& lo, glm::ivec3& hi) {
  dvec3 pad = n.cell_size * cell_padding;
  for (int a = 0; a < 3; ++a) {
    lo[a] = int(std::floor((b.lower[a] - pad[a] - n.box.lower[a]) / n.cell_size[a]));
    hi[a] = int(std::floor((b.upper[a] + pad[a] - n.box.lower[a]) / n.cell_size[a]));
    lo[a] = std::clamp(lo[a], 0, n.resolution[a] - 1);
    hi[a] = std::clamp(hi[a], 0, n.resolution[a] - 1);
  }
}

struct builder {
  const item_bounds_function& bounds;
  const item_overlap_function& overlaps;
  const grid_options& options;
  grid& out;

  // Builds one node over box from candidate items; returns its index. Cells holding too many items
  // become child nodes while depth allows.
  int32_t build_node(const bounds3& box, const glm::ivec3& resolution,
                     const std::vector<uint32_t>& candidates, int depth) {
    grid_node node;
    node.box = box;
    node.resolution = resolution;
    node.cell_size = box.diagonal() / dvec3(resolution);
    const size_t cell_count = size_t(resolution.x) * resolution.y * resolution.z;
    node.first_cell = uint32_t(out.cells.size());
    KILN_CHECK(out.cells.size() + cell_count < size_t(UINT32_MAX));
    const int32_t node_index = int32_t(out.nodes.size());
    out.nodes.push_back(node);
    out.cells.resize(out.cells.size() + cell_count);

    // (cell, item) pairs, then a counting sort by cell: two flat arrays instead of a vector per cell.
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    pairs.reserve(candidates.size() * 2);
    for (uint32_t item : candidates) {
      bounds3 b = bounds(item);
      if (b.empty()) continue;
      glm::ivec3 lo, hi;
      cell_range(node, b, lo, hi);
      const bool single = lo == hi;
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) {
            glm::ivec3 c(x, y, z);
            // An item whose bounds fit in one cell overlaps it; skip the exact test.
            if (single || overlaps(item, cell_box(node, c)))
              pairs.emplace_back(node.cell_index(c) - node.first_cell, item);
          }
    }
    std::vector<uint32_t> offsets(cell_count + 1, 0);
    for (const auto& p : pairs) ++offsets[p.first + 1];
    for (size_t i = 0; i < cell_count; ++i) offsets[i + 1] += offsets[i];
    std::vector<uint32_t> sorted(pairs.size());
    {
      std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
      for (const auto& p : pairs) sorted[cursor[p.first]++] = p.second;
    }
    pairs = {};

    for (size_t i = 0; i < cell_count; ++i) {
      const uint32_t count = offsets[i + 1] - offsets[i];
      if (depth < options.max_depth && count > uint32_t(options.max_items_per_cell)) {
        glm::ivec3 c(int(i % resolution.x), int(i / resolution.x % resolution.y),
                     int(i / (size_t(resolution.x) * resolution.y)));
        dvec3 lower = box.lower + dvec3(c) * node.cell_size;
        std::vector<uint32_t> inside(sorted.begin() + offsets[i], sorted.begin() + offsets[i + 1]);
        int32_t child = build_node(bounds3{lower, lower + node.cell_size},
                                   glm::ivec3(options.child_resolution), inside, depth + 1);
        out.cells[node.first_cell + i].child = child;
        continue;
      }
      grid_cell& cell = out.cells[node.first_cell + i];
      cell.first = uint32_t(out.items.size());
      cell.count = count;
      out.items.insert(out.items.end(), sorted.begin() + offsets[i], sorted.begin() + offsets[i + 1]);
    }
    return node_index;
  }
};

}  // namespace

grid_options uniform_grid_options() { return grid_options{}; }

grid_options adaptive_grid_options() {
  grid_options o;
  o.max_items_per_cell = 8;
  o.max_depth = 3;
  return o;
}

glm::ivec3 grid_resolution(const bounds3& box, size_t item_count, const grid_options& options) {
  if (options.resolution) return glm::max(*options.resolution, glm::ivec3(1));
  dvec3 extent = box.diagonal();
  double largest = std::max({extent.x, extent.y, extent.z});
  if (!(largest > 0.0) || item_count == 0) return glm::ivec3(1);
  // Axes thinner than a thousandth of the largest count as flat, so a planar mesh gets a 2D grid.
  double volume = 1.0;
  int dimensions = 0;
  for (int a = 0; a < 3; ++a)
    if (extent[a] > largest * 1e-3) {
      volume *= extent[a];
      ++dimensions;
    }
  double side = std::pow(volume / (options.density * double(item_count)), 1.0 / dimensions);
  glm::ivec3 res;
  for (int a = 0; a < 3; ++a) {
    double cells = extent[a] > largest * 1e-3 ? std::ceil(extent[a] / side) : 1.0;
    res[a] = int(std::clamp(cells, 1.0, double(std::max(1, options.max_resolution))));
  }
  return res;
}

grid build_grid(uint32_t item_count, const item_bounds_function& item_bounds,
                const item_overlap_function& overlaps, const grid_options& options) {
  grid out;
  bounds3 all;
  std::vector<uint32_t> candidates;
  candidates.reserve(item_count);
  for (uint32_t i = 0; i < item_count; ++i) {
    bounds3 b = item_bounds(i);
    if (b.empty() || !is_finite(b.lower) || !is_finite(b.upper)) continue;
    all.extend(b);
    candidates.push_back(i);
  }
  if (candidates.empty()) return out;
  bounds3 root = padded_root(all);
  builder b{item_bounds, overlaps, options, out};
  b.build_node(root, grid_resolution(root, candidates.size(), options), candidates, 0);
  out.nodes.shrink_to_fit();
  out.cells.shrink_to_fit();
  out.items.shrink_to_fit();
  return out;
}

}  // namespace kiln
