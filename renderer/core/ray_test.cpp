#include "core/ray.h"

#include <gtest/gtest.h>

#include <limits>

namespace kiln {
namespace {

// Every clause of is_valid rejects exactly the rays Embree must never see.
TEST(ray, validity_rejects_each_kind_of_bad_ray) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ray good;
  good.origin = {1, 2, 3};
  good.direction = {0, 0, -1};
  good.tmin = 0.0f;
  good.tmax = 10.0f;
  EXPECT_TRUE(is_valid(good));
  ray unbounded = good;
  unbounded.tmax = inf;  // an infinite extent is fine
  EXPECT_TRUE(is_valid(unbounded));
  ray point = good;
  point.tmin = point.tmax = 2.0f;  // empty open interval, but not invalid for Embree
  EXPECT_TRUE(is_valid(point));

  auto broken = [&](auto change) {
    ray r = good;
    change(r);
    return !is_valid(r);
  };
  EXPECT_TRUE(broken([&](ray& r) { r.origin.x = nan; }));
  EXPECT_TRUE(broken([&](ray& r) { r.origin.y = inf; }));
  EXPECT_TRUE(broken([&](ray& r) { r.direction.z = nan; }));
  EXPECT_TRUE(broken([&](ray& r) { r.direction.x = -inf; }));
  EXPECT_TRUE(broken([&](ray& r) { r.direction = vec3(0.0f); }));
  EXPECT_TRUE(broken([&](ray& r) { r.direction = vec3(1e-30f, 0.0f, 0.0f); }));  // squares to zero
  EXPECT_TRUE(broken([&](ray& r) { r.tmin = nan; }));
  EXPECT_TRUE(broken([&](ray& r) { r.tmax = nan; }));
  EXPECT_TRUE(broken([&](ray& r) { r.tmin = -1.0f; }));
  EXPECT_TRUE(broken([&](ray& r) { r.tmin = 11.0f; }));  // tmin > tmax
}

}  // namespace
}  // namespace kiln
