// Whitted's adaptive refinement on analytic pictures: a half-plane whose pixel coverage is known.
#include "render/adaptive_sampling.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

// Alpha 1 (instance 0) where x > edge, nothing elsewhere; counts calls.
struct vertical_edge {
  double edge;
  int calls = 0;
  camera_sample operator()(double x, double) {
    ++calls;
    camera_sample s;
    if (x > edge) {
      s.rgba = vec4(1.0f);
      s.instance = 0;
      s.depth = 2.0f;
    }
    return s;
  }
};

adaptive_pixel refine(vertical_edge& picture, int depth, double px = 0.0) {
  adaptive_options options{0.1f, depth};
  camera_sample corners[4] = {picture(px, 0), picture(px + 1, 0), picture(px, 1), picture(px + 1, 1)};
  picture.calls = 0;
  adaptive_scratch scratch;
  sample_tracer trace = [&picture](double x, double y) { return picture(x, y); };
  return refine_pixel(int(px), 0, corners, options, trace, scratch);
}

TEST(adaptive_sampling, uniform_pixel_traces_nothing_beyond_its_corners) {
  vertical_edge picture{-5.0};
  adaptive_pixel p = refine(picture, 3);
  EXPECT_EQ(picture.calls, 0);
  EXPECT_EQ(p.rgba, vec4(1.0f));
  EXPECT_EQ(p.nearest.depth, 2.0f);
}

TEST(adaptive_sampling, an_edge_splits_only_the_squares_it_crosses) {
  vertical_edge picture{0.3};
  // Depth 1: one split, five new points (four edge midpoints and the centre); the halves
  // x < 0.5 average to 0.5 and x > 0.5 to 1.
  adaptive_pixel one = refine(picture, 1);
  EXPECT_EQ(picture.calls, 5);
  EXPECT_FLOAT_EQ(one.rgba.a, 0.75f);
  // Depth 2: the two left quarters split again (5 + 4 new points, their shared midpoint traced
  // once); their cells at x < 0.25 see 0, at 0.25..0.5 half: (0.25 + 1) / 2.
  adaptive_pixel two = refine(picture, 2);
  EXPECT_EQ(picture.calls, 14);
  EXPECT_FLOAT_EQ(two.rgba.a, 0.625f);
}

TEST(adaptive_sampling, coverage_converges_to_the_area_as_depth_grows) {
  // Alpha converges to the covered area 1 - edge: only the column of cells (2^-D wide) that the
  // edge cuts is wrong, by at most half its area, so the error bound halves with each level.
  for (double edge : {0.3, 0.61, 0.137}) {
    for (int depth = 1; depth <= 6; ++depth) {
      vertical_edge picture{edge};
      double error = std::abs(refine(picture, depth).rgba.a - (1.0 - edge));
      EXPECT_LE(error, 0.5 / (1 << depth) + 1e-6) << edge << " depth " << depth;
    }
  }
}

TEST(adaptive_sampling, differing_instances_split_even_below_the_threshold) {
  camera_sample a, b;
  a.instance = 1;
  b.instance = 2;
  EXPECT_TRUE(corners_differ(a, a, a, b, 1e9f));
  EXPECT_FALSE(corners_differ(a, a, a, a, 0.01f));
  camera_sample c = a;
  c.rgba.g = 0.02f;
  EXPECT_TRUE(corners_differ(a, c, a, a, 0.01f));
  EXPECT_FALSE(corners_differ(a, c, a, a, 0.03f));
}

}  // namespace
}  // namespace kiln
