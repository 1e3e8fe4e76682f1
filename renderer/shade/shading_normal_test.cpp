#include "shade/shading_normal.h"

#include <gtest/gtest.h>

#include <random>

namespace kiln {
namespace {

vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(vec3(g(rng), g(rng), g(rng)));
}

float mirrored_height(const vec3& n, const vec3& v, const vec3& ng) {
  return glm::dot(2.0f * glm::dot(n, v) * n - v, ng);
}

TEST(shading_normal, a_normal_facing_away_from_a_grazing_viewer_is_bent_just_enough) {
  // Viewer 80° from the geometric normal, shading normal tilted 30° away from it: n·v < 0.
  const vec3 ng(0, 0, 1);
  const vec3 v(std::sin(glm::radians(80.0f)), 0, std::cos(glm::radians(80.0f)));
  const vec3 n(-0.5f, 0, std::sqrt(0.75f));
  ASSERT_LT(glm::dot(n, v), 0.0f);
  const vec3 bent = bend_toward_viewer(ng, v, n);
  EXPECT_NEAR(glm::length(bent), 1.0f, 1e-6f);
  EXPECT_GT(glm::dot(bent, v), 0.0f);
  // The mirror image sits exactly at the threshold min(0.9·cos 80°, 0.01) = 0.01.
  EXPECT_NEAR(mirrored_height(bent, v, ng), 0.01f, 1e-5f);
  // The bend stays in the plane of n and ng, between them.
  EXPECT_NEAR(bent.y, 0.0f, 1e-7f);
  EXPECT_LT(bent.x, 0.0f);
  EXPECT_GT(bent.z, n.z);
}

TEST(shading_normal, valid_normals_are_returned_unchanged) {
  const vec3 ng(0, 0, 1);
  EXPECT_EQ(bend_toward_viewer(ng, ng, ng), ng);
  const vec3 v = glm::normalize(vec3(1, 0, 1));
  const vec3 n = glm::normalize(vec3(0.3f, 0.2f, 1.0f));
  EXPECT_EQ(bend_toward_viewer(ng, v, n), n);
}

TEST(shading_normal, random_normals_always_face_the_viewer_after_bending) {
  std::mt19937 rng(7);
  int bent_count = 0;
  for (int i = 0; i < 100000; ++i) {
    const vec3 ng = random_unit(rng);
    vec3 v = random_unit(rng), n = random_unit(rng);
    if (glm::dot(v, ng) < 0.0f) v = -v;
    if (glm::dot(n, ng) < 0.0f) n = -n;
    if (!(glm::dot(v, ng) > 1e-4f)) continue;
    const vec3 bent = bend_toward_viewer(ng, v, n);
    if (bent != n) ++bent_count;
    ASSERT_NEAR(glm::length(bent), 1.0f, 1e-5f) << i;
    ASSERT_GT(glm::dot(bent, v), 0.0f) << i;
    ASSERT_GE(glm::dot(bent, ng), 0.0f) << i;
    const float threshold = std::min(0.9f * glm::dot(v, ng), 0.01f);
    ASSERT_GE(mirrored_height(bent, v, ng), threshold - 2e-5f) << i;
  }
  EXPECT_GT(bent_count, 10000);  // the case is common, not a corner
}

}  // namespace
}  // namespace kiln
