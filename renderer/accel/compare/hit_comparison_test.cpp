#include "accel/compare/hit_comparison.h"

#include <gtest/gtest.h>

#include "geometry/watertight_triangle.h"

namespace kiln {
namespace {

// Two coincident unit squares in z = 0 (instances 0 and 1), front face +Z.
scene coincident_squares() {
  scene s;
  mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  s.meshes.push_back(m);
  s.materials.emplace_back();
  instance inst;
  finish_instance_transform(inst);
  s.instances = {inst, inst};
  return s;
}

hit make_hit(uint32_t instance, uint32_t primitive, float t, float u, float v) {
  return hit{t, instance, primitive, u, v, vec3(0, 0, 1)};
}

TEST(hit_comparison, classifies_agreement_ties_edges_and_mismatches) {
  scene s = coincident_squares();
  ray r;
  r.origin = {0.3f, -0.5f, 2.0f};
  r.direction = {0, 0, -1};
  const hit a = make_hit(0, 0, 2.0f, 0.4f, 0.25f);
  EXPECT_EQ(compare_hits(s, r, std::nullopt, std::nullopt), hit_verdict::agree);
  EXPECT_EQ(compare_hits(s, r, a, a), hit_verdict::agree);
  // The same primitive a few ulps apart agrees; a thousandth apart does not.
  EXPECT_EQ(compare_hits(s, r, a, make_hit(0, 0, 2.0000005f, 0.4f, 0.25f)), hit_verdict::agree);
  EXPECT_EQ(compare_hits(s, r, a, make_hit(0, 0, 2.002f, 0.4f, 0.25f)), hit_verdict::mismatch);
  // The coincident copy at the same t is a genuine tie; at another t it is a mismatch.
  EXPECT_EQ(compare_hits(s, r, a, make_hit(1, 0, 2.0f, 0.4f, 0.25f)), hit_verdict::tie);
  EXPECT_EQ(compare_hits(s, r, a, make_hit(1, 0, 2.5f, 0.4f, 0.25f)), hit_verdict::mismatch);
  // A miss against a hit inside the triangle is a mismatch; against a hit on an edge it is not.
  EXPECT_EQ(compare_hits(s, r, a, std::nullopt), hit_verdict::mismatch);
  EXPECT_EQ(compare_hits(s, r, std::nullopt, make_hit(0, 0, 2.0f, 0.5f, 0.0f)), hit_verdict::edge);
  // A hit right at the segment's start (the surface the ray left) is a boundary case.
  ray from_surface = r;
  from_surface.origin.z = 1e-7f;
  EXPECT_TRUE(hit_on_boundary(s, from_surface, make_hit(0, 0, 1e-7f, 0.4f, 0.25f)));
  EXPECT_FALSE(hit_on_boundary(s, r, a));
}

TEST(hit_comparison, tolerance_grows_for_grazing_rays) {
  scene s = coincident_squares();
  ray head_on, grazing;
  head_on.origin = {0.2f, 0.2f, 1.0f};
  head_on.direction = {0, 0, -1};
  grazing.direction = glm::normalize(vec3(1.0f, 0.0f, -1e-3f));
  const hit h = make_hit(0, 0, 1.0f, 0.3f, 0.3f);
  EXPECT_GT(hit_t_tolerance(s, grazing, h), 100.0f * hit_t_tolerance(s, head_on, h));
  EXPECT_LT(hit_t_tolerance(s, head_on, h), 1e-4f);  // a hundredth of the 2.002 mismatch above
}

// The ray and triangles of BrainStem's Draco variant where Embree and the grid first differed
// (world = object space): a sliver 2e-4 ahead of the origin, and the next surface at t = 0.0762.
scene sliver_and_far_triangle() {
  scene s;
  mesh m;
  m.positions = {{-0.473637223f, 0.588905215f, 0.0383402109f}, {-0.557630599f, 1.06347823f, 0.0569752194f},
                 {-0.55919832f, 1.059811f, 0.0639763847f},     {-0.539258182f, 1.10274816f, 0.0368428193f},
                 {-0.551864803f, 1.10058439f, 0.0356103368f},  {-0.472104579f, 0.723029912f, 0.0218235943f}};
  m.indices = {0, 1, 2, 3, 4, 5};
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  s.meshes.push_back(m);
  s.materials.emplace_back();
  instance inst;
  finish_instance_transform(inst);
  s.instances = {inst};
  return s;
}

TEST(hit_comparison, hit_inside_the_watertight_t_bound_is_a_boundary_case_not_a_mismatch) {
  const scene s = sliver_and_far_triangle();
  ray r;
  r.origin = {-0.547467351f, 0.998210132f, 0.0587481447f};
  r.direction = {0.465793997f, -0.801093042f, -0.375880182f};
  const mesh& m = s.meshes[0];
  // The hit is real: in double precision the ray meets the sliver at t = 1.989e-4, inside it.
  const dvec3 p0(m.positions[0]), e1 = dvec3(m.positions[1]) - p0, e2 = dvec3(m.positions[2]) - p0;
  const dvec3 d(r.direction), pv = glm::cross(d, e2), tv = dvec3(r.origin) - p0, qv = glm::cross(tv, e1);
  const double det = glm::dot(e1, pv), u = glm::dot(tv, pv) / det, v = glm::dot(d, qv) / det;
  EXPECT_NEAR(glm::dot(e2, qv) / det, 1.989e-4, 1e-6);
  EXPECT_GT(std::min({u, v, 1.0 - u - v}), 0.1);
  // The watertight test refuses it (t is below its error bound), so the grid reports the far one.
  triangle_hit th;
  const sheared_ray sheared = shear_ray(r.origin, r.direction);
  EXPECT_FALSE(intersect_watertight(sheared, m.positions[0], m.positions[1], m.positions[2], 0.0f, inf, th));
  ASSERT_TRUE(intersect_watertight(sheared, m.positions[3], m.positions[4], m.positions[5], 0.0f, inf, th));
  const hit embree_hit = make_hit(0, 0, 1.9892e-4f, 0.2695f, 0.5972f),
            grid_hit = make_hit(0, 1, th.t, th.u, th.v);
  EXPECT_TRUE(within_watertight_t_bound(s, r, embree_hit));
  EXPECT_EQ(compare_hits(s, r, embree_hit, grid_hit), hit_verdict::edge);
  // Narrow: from 0.01 farther back the test accepts the sliver, and a backend skipping it is wrong.
  ray back = r;
  back.origin = r.origin - 0.01f * r.direction;
  EXPECT_TRUE(intersect_watertight(shear_ray(back.origin, back.direction), m.positions[0], m.positions[1],
                                   m.positions[2], 0.0f, inf, th));
  const hit near_hit = make_hit(0, 0, th.t, th.u, th.v);
  EXPECT_FALSE(within_watertight_t_bound(s, back, near_hit));
  EXPECT_EQ(compare_hits(s, back, near_hit, make_hit(0, 1, grid_hit.t + 0.01f, grid_hit.u, grid_hit.v)),
            hit_verdict::mismatch);
}

}  // namespace
}  // namespace kiln
