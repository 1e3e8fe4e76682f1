#include "accel/compare/hit_comparison.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace kiln
