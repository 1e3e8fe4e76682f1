#include "render/deep_pixel.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

deep_sample at(float z, float instance, vec4 rgba) {
  deep_sample s;
  s.z = s.z_back = z;
  s.instance = instance;
  s.rgba = rgba;
  return s;
}

// Front to back with `over`, as a deep flatten does.
vec4 flatten(const std::vector<deep_sample>& samples) {
  vec4 sum(0.0f);
  float transmittance = 1.0f;
  for (const deep_sample& s : samples) {
    sum += transmittance * s.rgba;
    transmittance *= 1.0f - s.rgba.a;
  }
  return sum;
}

TEST(deep_pixel, one_surface_within_the_tolerance_merges_to_its_front_and_farthest_back) {
  std::vector<deep_sample> samples = {at(2.01f, 3, vec4(0.1f, 0, 0, 0.25f)),
                                      at(2.0f, 3, vec4(0.2f, 0, 0, 0.25f)),
                                      at(2.0f * (1 + 2 * deep_merge_tolerance), 3, vec4(0, 0.5f, 0, 0.5f))};
  merge_deep_samples(samples);
  ASSERT_EQ(samples.size(), 2u);  // the third lies past the tolerance of the front
  EXPECT_EQ(samples[0].z, 2.0f);
  EXPECT_EQ(samples[0].z_back, 2.01f);
  EXPECT_FLOAT_EQ(samples[0].rgba.r, 0.3f);
  EXPECT_FLOAT_EQ(samples[0].rgba.a, 0.5f);
  EXPECT_EQ(samples[1].rgba.g, 0.5f);
}

TEST(deep_pixel, a_surface_spanning_depths_inside_the_pixel_chains_into_one_sample) {
  // A wall at a grazing angle: each sample within 1% of the one before, 3% from first to last.
  std::vector<deep_sample> samples = {at(2.03f, 5, vec4(0, 0, 0, 0.25f)), at(2.0f, 5, vec4(0, 0, 0, 0.25f)),
                                      at(2.015f, 5, vec4(0, 0, 0, 0.5f))};
  merge_deep_samples(samples);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].z, 2.0f);
  EXPECT_EQ(samples[0].z_back, 2.03f);
  EXPECT_FLOAT_EQ(samples[0].rgba.a, 1.0f);
}

TEST(deep_pixel, other_surfaces_at_the_same_depth_stay_apart_and_are_not_tidy) {
  std::vector<deep_sample> samples = {at(1.0f, 1, vec4(0, 0, 0, 0.5f)), at(1.0f, 2, vec4(0, 0, 0, 0.5f))};
  merge_deep_samples(samples);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].instance, 1.0f);
  EXPECT_FALSE(deep_samples_tidy(samples));
  samples[1].z = samples[1].z_back = 1.5f;
  EXPECT_TRUE(deep_samples_tidy(samples));
  samples[0].z_back = 1.6f;  // a merged front sample reaching past the next one's front
  EXPECT_FALSE(deep_samples_tidy(samples));
}

TEST(deep_pixel, over_form_flattens_to_the_additive_sum) {
  // Coverage shares: a BLEND layer 0.3 of the pixel, the surface behind 0.6, an edge 0.1 open.
  std::vector<deep_sample> samples = {at(1.0f, 0, vec4(0.3f, 0.1f, 0.0f, 0.3f)),
                                      at(2.0f, 1, vec4(0.0f, 0.4f, 0.2f, 0.6f))};
  const vec4 sum = samples[0].rgba + samples[1].rgba;
  to_over_form(samples);
  EXPECT_FLOAT_EQ(samples[0].rgba.a, 0.3f);
  EXPECT_FLOAT_EQ(samples[1].rgba.a, 0.6f / 0.7f);
  const vec4 flat = flatten(samples);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(flat[c], sum[c], 1e-7f) << c;
}

TEST(deep_pixel, what_lies_behind_a_covered_pixel_folds_into_the_sample_in_front) {
  std::vector<deep_sample> samples = {at(1.0f, 0, vec4(0.5f, 0, 0, 1.0f)),
                                      at(3.0f, 1, vec4(0.25f, 0, 0, 0.0f))};
  to_over_form(samples);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].z_back, 3.0f);
  EXPECT_FLOAT_EQ(flatten(samples).r, 0.75f);
}

}  // namespace
}  // namespace kiln
