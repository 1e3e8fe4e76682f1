#include "core/float_bits.h"

#include <gtest/gtest.h>

#include <random>

namespace kiln {
namespace {

TEST(float_bits, next_float_moves_by_one_ulp) {
  EXPECT_GT(next_float_up(1.0f), 1.0f);
  EXPECT_EQ(next_float_up(1.0f), 1.0f + std::numeric_limits<float>::epsilon());
  EXPECT_LT(next_float_down(1.0f), 1.0f);
  EXPECT_GT(next_float_up(0.0f), 0.0f);
  EXPECT_LT(next_float_down(0.0f), 0.0f);
  EXPECT_GT(next_float_up(-1.0f), -1.0f);
  EXPECT_EQ(next_float_up(inf), inf);
}

TEST(float_bits, gamma_bound_grows_with_operation_count) {
  EXPECT_GT(gamma_bound(3), 3 * machine_epsilon);
  EXPECT_LT(gamma_bound(3), 3.01f * machine_epsilon);
  EXPECT_GT(gamma_bound(7), gamma_bound(3));
}

// Property: the offset origin lies strictly on the side of the plane the direction points to,
// by more than the stated error, for points far from the origin as well as near it.
TEST(float_bits, offset_origin_leaves_the_error_box_on_the_right_side) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (float scale : {1e-3f, 1.0f, 1e4f, 1e7f}) {
    for (int i = 0; i < 1000; ++i) {
      vec3 p = vec3(unit(rng), unit(rng), unit(rng)) * scale;
      vec3 n = glm::normalize(vec3(unit(rng), unit(rng), unit(rng)) + vec3(0.0f, 0.0f, 1e-3f));
      vec3 error = glm::abs(p) * gamma_bound(7);
      vec3 w = unit(rng) > 0 ? n : -n;
      vec3 po = offset_ray_origin(p, error, n, w);
      double side = glm::dot(dvec3(po) - dvec3(p), dvec3(n));
      double reach = glm::dot(glm::abs(dvec3(n)), dvec3(error));
      if (glm::dot(w, n) > 0)
        EXPECT_GE(side, reach * 0.999);
      else
        EXPECT_LE(side, -reach * 0.999);
    }
  }
}

}  // namespace
}  // namespace kiln
