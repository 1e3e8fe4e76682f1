#include "geometry/watertight_triangle.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace kiln {
namespace {

bool hit_triangle(const vec3& o, const vec3& d, const vec3& p0, const vec3& p1, const vec3& p2,
                  triangle_hit& h) {
  return intersect_watertight(shear_ray(o, d), p0, p1, p2, 0.0f, inf, h);
}

TEST(watertight_triangle, barycentrics_follow_embree_convention) {
  const vec3 p0(0, 0, 0), p1(2, 0, 0), p2(0, 4, 0);
  triangle_hit h;
  ASSERT_TRUE(hit_triangle({0.5f, 1.0f, 3.0f}, {0, 0, -1}, p0, p1, p2, h));
  EXPECT_FLOAT_EQ(h.t, 3.0f);
  EXPECT_FLOAT_EQ(h.u, 0.25f);  // weight of p1: x = 2u
  EXPECT_FLOAT_EQ(h.v, 0.25f);  // weight of p2: y = 4v
  // Both faces: from below, same barycentrics.
  ASSERT_TRUE(hit_triangle({0.5f, 1.0f, -2.0f}, {0, 0, 1}, p0, p1, p2, h));
  EXPECT_FLOAT_EQ(h.t, 2.0f);
  EXPECT_FLOAT_EQ(h.u, 0.25f);
  EXPECT_FLOAT_EQ(h.v, 0.25f);
  // u != v, so a swap of the two weights cannot pass: x = 0.2 -> u = 0.1, y = 3 -> v = 0.75.
  ASSERT_TRUE(hit_triangle({0.2f, 3.0f, 1.0f}, {0, 0, -1}, p0, p1, p2, h));
  EXPECT_FLOAT_EQ(h.u, 0.1f);
  EXPECT_FLOAT_EQ(h.v, 0.75f);
  // Winding does not matter to the convention: with p1 and p2 exchanged, so are u and v.
  ASSERT_TRUE(hit_triangle({0.2f, 3.0f, 1.0f}, {0, 0, -1}, p0, p2, p1, h));
  EXPECT_FLOAT_EQ(h.u, 0.75f);
  EXPECT_FLOAT_EQ(h.v, 0.1f);
}

TEST(watertight_triangle, accepts_t_in_half_open_tmin_tmax_and_misses_outside) {
  const vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
  sheared_ray r = shear_ray({0.2f, 0.2f, 1.0f}, {0, 0, -1});
  triangle_hit h;
  EXPECT_TRUE(intersect_watertight(r, p0, p1, p2, 0.0f, 1.0f, h));
  EXPECT_FALSE(intersect_watertight(r, p0, p1, p2, 0.0f, 0.999f, h));
  EXPECT_FALSE(intersect_watertight(r, p0, p1, p2, 1.001f, 5.0f, h));
  EXPECT_FALSE(intersect_watertight(r, p0, p1, p2, 1.0f, 5.0f, h));  // t == tmin is excluded, as in Embree
  EXPECT_FALSE(hit_triangle({0.6f, 0.6f, 1.0f}, {0, 0, -1}, p0, p1, p2, h));
  // A ray in the triangle's plane never hits it (determinant 0), and produces no NaN.
  EXPECT_FALSE(hit_triangle({-1.0f, 0.2f, 0.0f}, {1, 0, 0}, p0, p1, p2, h));
}

TEST(watertight_triangle, reconstructed_point_matches_ray_point_on_random_rays) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng)), p2(u(rng), u(rng), u(rng));
    vec3 o = 3.0f * vec3(u(rng), u(rng), u(rng));
    vec3 target = (p0 + p1 + p2) / 3.0f + 0.5f * vec3(u(rng), u(rng), u(rng));
    triangle_hit h;
    if (!hit_triangle(o, target - o, p0, p1, p2, h)) continue;
    ++hits;
    vec3 q = (1 - h.u - h.v) * p0 + h.u * p1 + h.v * p2;
    vec3 r = o + h.t * (target - o);
    EXPECT_LT(glm::length(q - r), 1e-4f) << i;
    EXPECT_GE(h.u, 0.0f);
    EXPECT_GE(h.v, 0.0f);
    EXPECT_LE(h.u + h.v, 1.0f + 1e-6f);
  }
  EXPECT_GT(hits, 2000);
}

// A closed octahedron: rays passing exactly through its shared vertices and through points on
// its shared edges must hit at least one triangle there, from every direction that is not in the
// plane of a face and that enter the solid there. Targets and origins are exact in float (dyadic fractions,
// integer directions, o = target - 4·d), so each ray really passes through the edge point and a miss is a
// slip.
TEST(watertight_triangle, no_ray_passes_between_triangles_of_a_closed_mesh) {
  const std::vector<vec3> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const std::vector<std::array<int, 3>> faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  std::vector<vec3> targets = v;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const vec3 a = v[size_t(f[size_t(k)])], b = v[size_t(f[size_t((k + 1) % 3)])];
      for (float s : {0.5f, 0.25f, 0.125f, 0.75f}) targets.push_back(a + s * (b - a));
    }
  int checked = 0;
  for (const vec3& target : targets)
    for (int dx = -3; dx <= 3; ++dx)
      for (int dy = -3; dy <= 3; ++dy)
        for (int dz = -3; dz <= 3; ++dz) {
          // Skip directions lying in a face plane (normals (±1, ±1, ±1)): coplanar rays see nothing.
          bool in_face_plane = false;
          for (int sy : {-1, 1})
            for (int sz : {-1, 1}) in_face_plane |= dx + sy * dy + sz * dz == 0;
          if (in_face_plane) continue;
          const vec3 d{float(dx), float(dy), float(dz)};
          // Rays that only touch the solid at a silhouette edge or vertex may pass it either way;
          // keep those that go into its interior right after or before the target.
          auto inside = [](const dvec3& p) { return std::abs(p.x) + std::abs(p.y) + std::abs(p.z) < 1.0; };
          if (!inside(dvec3(target) + 1e-3 * dvec3(d)) && !inside(dvec3(target) - 1e-3 * dvec3(d))) continue;
          const vec3 o = target - 4.0f * d;
          int hits = 0;
          for (const auto& f : faces) {
            triangle_hit h;
            // Count only hits at the target point (the ray may also cross the far side).
            if (hit_triangle(o, d, v[size_t(f[0])], v[size_t(f[1])], v[size_t(f[2])], h) &&
                glm::length(o + h.t * d - target) < 1e-5f)
              ++hits;
          }
          EXPECT_GE(hits, 1) << "slipped through at " << target.x << "," << target.y << "," << target.z
                             << " d=" << dx << "," << dy << "," << dz;
          ++checked;
        }
  EXPECT_GT(checked, 3000);
}

// A fan of triangles around one vertex, tessellating a flat square: rays straight at the shared
// vertex and the shared edges always hit the plane.
TEST(watertight_triangle, shared_vertex_of_a_fan_is_hit) {
  const int n = 7;
  std::vector<vec3> ring;
  for (int i = 0; i < n; ++i) {
    float a = 2.0f * pi * float(i) / float(n);
    ring.push_back({std::cos(a), std::sin(a), 0.0f});
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    vec3 d = glm::normalize(vec3(0.3f * u(rng), 0.3f * u(rng), -1.0f));
    vec3 target = i % 2 ? vec3(0.0f) : 0.37f * ring[size_t(i % n)];  // the centre, or a spoke
    vec3 o = target - 3.7f * d;
    int hits = 0;
    for (int k = 0; k < n; ++k) {
      triangle_hit h;
      if (hit_triangle(o, d, vec3(0.0f), ring[size_t(k)], ring[size_t((k + 1) % n)], h)) ++hits;
    }
    EXPECT_GE(hits, 1) << i;
  }
}

}  // namespace
}  // namespace kiln
