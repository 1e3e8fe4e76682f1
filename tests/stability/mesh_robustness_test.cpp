// Rays through the shared edges and vertices of a closed mesh, and meshes with degenerate
// triangles, through kiln's watertight test (the grid backend's, geometry/watertight_triangle.h)
// and Embree (kiln's default backend; asserted for degenerate triangles, measured for edges), against the
// textbook Möller–Trumbore test in float (bench/stability/naive_triangle.h), which must slip through or
// return a non-finite hit somewhere.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/synthetic_scenes.h"
#include "geometry/watertight_triangle.h"
#include "io/gltf/gltf_loader.h"
#include "ray_budget.h"
#include "stability/naive_triangle.h"
#include "support/gltf_builder.h"

namespace kiln::bench {
namespace {

struct edge_ray {
  ray r;
  vec3 target;
};

// Rays entering a closed sphere mesh exactly at its vertices and at points on its edges, from
// random directions at least 11° off the surface's tangent plane.
std::vector<edge_ray> edge_and_vertex_rays(const mesh& m, const vec3& centre, int per_target) {
  std::vector<vec3> targets = m.positions;
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const vec3 a = m.positions[m.indices[i + size_t(k)]],
                 b = m.positions[m.indices[i + size_t((k + 1) % 3)]];
      targets.push_back(a + 0.5f * (b - a));
      targets.push_back(a + 0.25f * (b - a));
    }
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<edge_ray> rays;
  for (const vec3& target : targets) {
    const vec3 outward = glm::normalize(target - centre);
    for (int k = 0; k < per_target;) {
      vec3 w(u(rng), u(rng), u(rng));
      if (glm::length(w) > 1.0f || glm::length(w) < 0.1f) continue;
      w = glm::normalize(w);
      if (glm::dot(w, outward) < 0.2f) continue;
      ++k;
      edge_ray e;
      e.r.origin = target + 3.0f * w;
      e.r.direction = -w;
      e.target = target;
      rays.push_back(e);
    }
  }
  return rays;
}

bool near_target(const edge_ray& e, float t) {
  return std::isfinite(t) && glm::length(e.r.origin + t * e.r.direction - e.target) < 1e-3f;
}

// The nearest hit over every triangle with a per-triangle test, or infinity.
template <typename Test>
float brute_force_nearest(const mesh& m, Test test) {
  float best = inf;
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    float t;
    if (test(m.positions[m.indices[i]], m.positions[m.indices[i + 1]], m.positions[m.indices[i + 2]], t))
      best = std::min(best, t);
  }
  return best;
}

TEST(stability_watertight, no_ray_slips_through_shared_edges_or_vertices_of_a_closed_mesh) {
  const vec3 centre(0.37f, -0.21f, 0.13f);
  mesh m = make_sphere_mesh(12, 24, 1.0f);
  m.bounds = {};
  for (vec3& p : m.positions) {
    p += centre;
    m.bounds.extend(dvec3(p));
  }
  const std::vector<edge_ray> rays = edge_and_vertex_rays(m, centre, testing::ray_budget(8));
  ASSERT_GT(rays.size(), 1000u);
  const scene s = scene_from_mesh(m);
  const embree_accelerator accel(s);
  int embree_slips = 0, watertight_slips = 0, naive_slips = 0;
  for (const edge_ray& e : rays) {
    const std::optional<hit> h = accel.intersect(e.r);
    if (!h || !near_target(e, h->t)) ++embree_slips;
    const sheared_ray sr = shear_ray(e.r.origin, e.r.direction);
    const float t_watertight =
        brute_force_nearest(m, [&](const vec3& a, const vec3& b, const vec3& c, float& t) {
          triangle_hit th;
          if (!intersect_watertight(sr, a, b, c, 0.0f, inf, th)) return false;
          t = th.t;
          return true;
        });
    if (!near_target(e, t_watertight)) ++watertight_slips;
    const float t_naive = brute_force_nearest(m, [&](const vec3& a, const vec3& b, const vec3& c, float& t) {
      naive_triangle_hit nh;
      if (!intersect_naive_triangle(e.r.origin, e.r.direction, a, b, c, nh)) return false;
      t = nh.t;
      return true;
    });
    if (!near_target(e, t_naive)) ++naive_slips;
  }
  // Embree (kiln's default backend, built without RTC_SCENE_FLAG_ROBUST) is measured, not yet
  // asserted: it misses ~7% of these rays (docs/stability.md, open finding).
  EXPECT_EQ(watertight_slips, 0) << "of " << rays.size();
  EXPECT_GT(naive_slips, 0) << "of " << rays.size();
  std::printf("%zu rays at shared edges and vertices: embree %d, watertight %d, naive %d slipped through\n",
              rays.size(), embree_slips, watertight_slips, naive_slips);
}

// The unit square z = 0 as two triangles, plus three degenerate ones inside it: a repeated vertex
// and three collinear vertices on the line x = 0.5, and a zero-area sliver along the shared diagonal.
mesh square_with_degenerates() {
  mesh m;
  m.positions = {{0, 0, 0},        {1, 0, 0},       {1, 1, 0},       {0, 1, 0},
                 {0.5f, 0.25f, 0}, {0.5f, 0.5f, 0}, {0.5f, 0.75f, 0}};
  m.indices = {0, 1, 2, 0, 2, 3, /* degenerate: */ 5, 4, 5, 4, 5, 6, 0, 5, 2};
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  return m;
}

TEST(stability_degenerate_triangles, never_hit_and_never_produce_a_non_finite_hit) {
  const mesh m = square_with_degenerates();
  const scene s = scene_from_mesh(m);
  const embree_accelerator accel(s);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int naive_non_finite = 0;
  const int rays = testing::ray_budget(4000);
  for (int i = 0; i < rays; ++i) {
    // Half of the rays go exactly through the degenerate triangles' lines (x = 0.5, y = x).
    const float a = u(rng), b = u(rng);
    vec3 target(0.05f + 0.9f * a, 0.05f + 0.9f * b, 0.0f);
    if (i % 4 == 1) target.x = 0.5f;
    if (i % 4 == 2) target.y = target.x;
    ray r;
    r.origin = target + vec3(0.3f * (u(rng) - 0.5f), 0.3f * (u(rng) - 0.5f), 2.0f);
    r.direction = glm::normalize(target - r.origin);
    const std::optional<hit> h = accel.intersect(r);
    ASSERT_TRUE(h) << i;
    EXPECT_LT(h->primitive_id, 2u) << "a degenerate triangle was hit, ray " << i;
    EXPECT_TRUE(std::isfinite(h->t) && std::isfinite(h->u) && std::isfinite(h->v)) << i;
    EXPECT_LT(glm::length(r.origin + h->t * r.direction - target), 1e-5f) << i;
    const sheared_ray sr = shear_ray(r.origin, r.direction);
    for (size_t k = 6; k < m.indices.size(); k += 3) {
      const vec3 p0 = m.positions[m.indices[k]], p1 = m.positions[m.indices[k + 1]],
                 p2 = m.positions[m.indices[k + 2]];
      triangle_hit th;
      EXPECT_FALSE(intersect_watertight(sr, p0, p1, p2, 0.0f, inf, th))
          << "ray " << i << " triangle " << k / 3;
      naive_triangle_hit nh;
      if (intersect_naive_triangle(r.origin, r.direction, p0, p1, p2, nh) &&
          !(std::isfinite(nh.t) && std::isfinite(nh.u) && std::isfinite(nh.v)))
        ++naive_non_finite;
    }
  }
  EXPECT_GT(naive_non_finite, 0);
}

TEST(stability_degenerate_triangles, the_loader_drops_them) {
  const mesh m = square_with_degenerates();
  testing::gltf_builder b;
  std::vector<std::array<float, 3>> positions;
  for (const vec3& p : m.positions) positions.push_back({p.x, p.y, p.z});
  b.add_node({{"mesh", b.add_mesh(positions, m.indices)}});
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "kiln_stability_degenerate.gltf";
  b.write(path.string());
  const scene s = load_gltf(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 6u);
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 3u);
}

}  // namespace
}  // namespace kiln::bench
