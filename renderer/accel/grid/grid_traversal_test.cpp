// Adversarial rays for the 3D-DDA: axis-parallel directions with +0.0 and -0.0 components, rays
// running along cell faces, edges and through cell corners, origins outside, on and inside the
// grid, rays grazing the grid bounds, and segments ending inside a cell. Every answer must equal
// the brute-force loop over all triangles exactly, and traversal must stay within its step bound.
#include "accel/grid/grid_traversal.h"

#include <gtest/gtest.h>

#include <random>

#include "accel/grid/mesh_grid.h"
#include "accel/grid/synthetic_scenes.h"
#include "geometry/triangle.h"
#include "geometry/watertight_triangle.h"

namespace kiln {
namespace {

struct test_ray {
  vec3 origin;
  vec3 direction;
  float tmin = 0.0f;
  float tmax = inf;
};

// The brute-force answer with the grid's tie rule (lowest primitive among equal t).
bool brute_force(const mesh& m, const test_ray& r, shape_hit& best) {
  sheared_ray s = shear_ray(r.origin, r.direction);
  bool found = false;
  for (uint32_t p = 0; p < m.triangle_count(); ++p) {
    auto v = triangle_vertices(m, p);
    triangle_hit h;
    if (!intersect_watertight(s, v[0], v[1], v[2], r.tmin, found ? best.t : r.tmax, h)) continue;
    if (found && !(h.t < best.t)) continue;
    best = shape_hit{h.t, p, h.u, h.v};
    found = true;
  }
  return found;
}

// A closed cube surface tessellated on the grid's own lattice (faces lie on cell planes), plus
// a diagonal sheet and a soup inside, so rays along planes meet triangles lying in those planes.
mesh adversarial_mesh() {
  mesh m;
  const int n = 4;
  auto add_quad = [&m](vec3 a, vec3 b, vec3 c, vec3 d) {
    uint32_t base = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c, d});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int di, int dj) {
            vec3 p(0.0f);
            p[axis] = side;
            p[(axis + 1) % 3] = -1.0f + 2.0f * float(i + di) / n;
            p[(axis + 2) % 3] = -1.0f + 2.0f * float(j + dj) / n;
            return p;
          };
          add_quad(corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1));
        }
  add_quad({-1, -1, -1}, {1, -1, -1}, {1, 1, 1}, {-1, 1, 1});  // a diagonal sheet through cell corners
  mesh soup = make_triangle_soup(200, 9, 0.8f, 0.2f);
  for (uint32_t idx : soup.indices) m.indices.push_back(uint32_t(m.positions.size()) + idx);
  m.positions.insert(m.positions.end(), soup.positions.begin(), soup.positions.end());
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  return m;
}

std::vector<test_ray> adversarial_rays(const grid_node& root) {
  std::vector<test_ray> rays;
  const dvec3 lo = root.box.lower, hi = root.box.upper;
  // Coordinates on the cell planes and at cell centres, per axis.
  std::vector<std::vector<float>> stops(3);
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k <= root.resolution[a]; ++k) {
      stops[size_t(a)].push_back(float(lo[a] + k * root.cell_size[a]));
      if (k < root.resolution[a]) stops[size_t(a)].push_back(float(lo[a] + (k + 0.5) * root.cell_size[a]));
    }
  // Axis-parallel rays along every cell edge line, face and centre line, both ways, with both
  // signed zeros, starting outside, on the box face, and inside.
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (float sign : {1.0f, -1.0f})
      for (float zero : {0.0f, -0.0f})
        for (float y : stops[size_t(b)])
          for (float z : stops[size_t(c)])
            for (int start = 0; start < 3; ++start) {
              test_ray r;
              r.direction[a] = sign;
              r.direction[b] = zero;
              r.direction[c] = zero;
              r.origin[b] = y;
              r.origin[c] = z;
              const float entry = float(sign > 0 ? lo[a] : hi[a]);
              r.origin[a] = start == 0 ? entry - sign * 3.0f : start == 1 ? entry : 0.1f;
              rays.push_back(r);
            }
  }
  // Diagonals through lattice corners, in all eight octants.
  for (int octant = 0; octant < 8; ++octant)
    for (size_t i = 0; i < stops[0].size(); i += 2)
      for (size_t j = 0; j < stops[1].size(); j += 2) {
        vec3 d((octant & 1) ? -1.0f : 1.0f, (octant & 2) ? -1.0f : 1.0f, (octant & 4) ? -1.0f : 1.0f);
        vec3 corner(stops[0][i], stops[1][j], stops[2][(i + j) % stops[2].size()]);
        rays.push_back({corner - 4.0f * d, d});
        rays.push_back({corner, d});  // origin on a corner, inside
      }
  // Grazing the bounds: origins on a face of the box, directions inside that face's plane.
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 3000; ++i) {
    const int a = i % 3;
    test_ray r;
    r.origin = vec3(1.5f * u(rng), 1.5f * u(rng), 1.5f * u(rng));
    r.origin[a] = float(i % 2 ? hi[a] : lo[a]);
    r.direction = vec3(u(rng), u(rng), u(rng));
    r.direction[a] = i % 4 < 2 ? 0.0f : -0.0f;
    rays.push_back(r);
  }
  // Random rays from inside and outside, with segments that end inside a cell or start late.
  for (int i = 0; i < 20000; ++i) {
    test_ray r;
    r.origin = (i % 2 ? 3.0f : 0.9f) * vec3(u(rng), u(rng), u(rng));
    r.direction = vec3(u(rng), u(rng), u(rng));
    if (i % 3 == 1) r.tmax = 0.5f + 2.0f * (u(rng) + 1.0f);
    if (i % 5 == 2) r.tmin = 0.3f * (u(rng) + 1.0f);
    rays.push_back(r);
  }
  return rays;
}

// Cells a ray may visit: sum(resolution) per node, times (3c - 2) child cells per level.
uint64_t step_bound(const grid_node& root, const grid_options& o) {
  uint64_t per_level = uint64_t(3 * o.child_resolution - 2), bound = 0, factor = 1;
  for (int level = 0; level <= o.max_depth; ++level, factor *= per_level) bound += factor;
  return uint64_t(root.resolution.x + root.resolution.y + root.resolution.z) * bound;
}

void check_against_brute_force(const grid_options& options) {
  const mesh m = adversarial_mesh();
  const mesh_grid g = build_mesh_grid(m, options);
  ASSERT_FALSE(g.cells.empty());
  const grid_node& root = g.cells.nodes[0];
  const std::vector<test_ray> rays = adversarial_rays(root);
  const uint64_t bound = step_bound(root, options);
  size_t hits = 0, mismatches = 0;
  uint64_t max_cells = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const test_ray& r = rays[i];
    shape_hit expected, got;
    const bool brute = brute_force(m, r, expected);
    traversal_counters counters;
    const bool found = intersect_mesh_grid(g, m, r.origin, r.direction, r.tmin, r.tmax, got, counters);
    max_cells = std::max(max_cells, counters.cells_visited);
    EXPECT_LE(counters.cells_visited, bound) << "ray " << i;
    const bool same =
        brute == found && (!brute || (expected.primitive == got.primitive && expected.t == got.t &&
                                      expected.u == got.u && expected.v == got.v));
    if (!same && ++mismatches <= 10)
      ADD_FAILURE() << "ray " << i << " o=(" << r.origin.x << "," << r.origin.y << "," << r.origin.z
                    << ") d=(" << r.direction.x << "," << r.direction.y << "," << r.direction.z << ") brute "
                    << brute << " prim " << expected.primitive << " t " << expected.t << ", grid " << found
                    << " prim " << got.primitive << " t " << got.t;
    traversal_counters occlusion_counters;
    EXPECT_EQ(occluded_mesh_grid(g, m, r.origin, r.direction, r.tmin, r.tmax, occlusion_counters), brute)
        << i;
    hits += brute;
  }
  EXPECT_EQ(mismatches, 0u) << "of " << rays.size() << " rays";
  EXPECT_GT(hits, rays.size() / 3);
  EXPECT_GT(rays.size(), 25000u);
  std::printf("adversarial rays: %zu, hits %zu, max cells visited %llu (bound %llu)\n", rays.size(), hits,
              (unsigned long long)max_cells, (unsigned long long)bound);
}

TEST(grid_traversal, uniform_grid_matches_brute_force_on_adversarial_rays) {
  grid_options o = uniform_grid_options();
  o.resolution = glm::ivec3(8, 8, 8);  // cell planes fall on the cube's tessellation
  check_against_brute_force(o);
}

TEST(grid_traversal, heuristic_grid_matches_brute_force_on_adversarial_rays) {
  check_against_brute_force(uniform_grid_options());
}

TEST(grid_traversal, adaptive_grid_matches_brute_force_on_adversarial_rays) {
  grid_options o = adaptive_grid_options();
  o.resolution = glm::ivec3(4, 4, 4);
  o.max_items_per_cell = 4;
  check_against_brute_force(o);
}

TEST(grid_traversal, clip_handles_zero_components_without_nan) {
  bounds3 box{dvec3(0.0), dvec3(1.0)};
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  // Origin on the face plane x = 0 with a zero x direction: inside the slab, no 0·inf.
  EXPECT_TRUE(clip_to_box(dda_ray{{0.0, 0.5, -1.0}, {-0.0, 0.0, 1.0}}, box, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 1.0);
  EXPECT_DOUBLE_EQ(t1, 2.0);
  t0 = 0.0;
  t1 = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(clip_to_box(dda_ray{{1.5, 0.5, -1.0}, {0.0, 0.0, 1.0}}, box, t0, t1));
}

TEST(grid_build, resolution_heuristic_follows_density_and_cap) {
  bounds3 box{dvec3(0.0), dvec3(4.0, 2.0, 1.0)};
  grid_options o;
  o.density = 1.0;
  glm::ivec3 res = grid_resolution(box, 8000, o);
  // 8000 cells over a 4:2:1 box: side = cbrt(8 / 8000) = 0.1.
  EXPECT_EQ(res, glm::ivec3(40, 20, 10));
  o.max_resolution = 16;
  EXPECT_EQ(grid_resolution(box, 8000, o), glm::ivec3(16, 16, 10));
  // A flat box gets one cell across its thin axis.
  EXPECT_EQ(grid_resolution(bounds3{dvec3(0.0), dvec3(1.0, 1.0, 0.0)}, 100, grid_options{}).z, 1);
  o.resolution = glm::ivec3(3, 5, 7);
  EXPECT_EQ(grid_resolution(box, 8000, o), glm::ivec3(3, 5, 7));
}

TEST(grid_build, triangles_land_only_in_cells_they_touch) {
  mesh m;
  // One long thin diagonal triangle across a 10³ grid: its bounds cover all 1000 cells, but it
  // touches only cells near the diagonal plane x = y.
  m.positions = {{0, 0, 0}, {1, 1, 0}, {1, 1, 1}};
  m.indices = {0, 1, 2};
  m.bounds = bounds3{dvec3(0.0), dvec3(1.0)};
  grid_options o;
  o.resolution = glm::ivec3(10);
  mesh_grid g = build_mesh_grid(m, o);
  EXPECT_GT(g.cells.items.size(), 10u);
  EXPECT_LT(g.cells.items.size(), 400u);
}

TEST(grid_build, adaptive_grid_splits_crowded_cells_until_depth) {
  mesh soup = make_triangle_soup(5000, 3, 1.0f, 0.01f);
  // Crowd one corner: a second dense cluster the top level cannot separate.
  mesh cluster = make_triangle_soup(5000, 4, 0.02f, 0.002f);
  for (uint32_t idx : cluster.indices) soup.indices.push_back(uint32_t(soup.positions.size()) + idx);
  soup.positions.insert(soup.positions.end(), cluster.positions.begin(), cluster.positions.end());
  grid_options o = adaptive_grid_options();
  mesh_grid adaptive = build_mesh_grid(soup, o);
  o.max_depth = 0;
  mesh_grid uniform = build_mesh_grid(soup, o);
  EXPECT_EQ(uniform.cells.nodes.size(), 1u);
  EXPECT_GT(adaptive.cells.nodes.size(), 1u);
  size_t largest_uniform = 0, largest_adaptive = 0;
  for (const grid_cell& c : uniform.cells.cells) largest_uniform = std::max<size_t>(largest_uniform, c.count);
  for (const grid_cell& c : adaptive.cells.cells)
    largest_adaptive = std::max<size_t>(largest_adaptive, c.count);
  EXPECT_LT(largest_adaptive, largest_uniform);
}

}  // namespace
}  // namespace kiln
