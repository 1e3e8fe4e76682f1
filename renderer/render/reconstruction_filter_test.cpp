// Filter kernels against their definitions, and the tile splat buffers' merge order.
#include "render/reconstruction_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "render/splat_film.h"

namespace kiln {
namespace {

const filter_kind all_kinds[] = {filter_kind::box, filter_kind::tent, filter_kind::gaussian,
                                 filter_kind::blackman_harris};

reconstruction_filter default_filter(filter_kind k) { return {k, default_filter_radius(k)}; }

// ∫ k(d) dd over [-r, r] by the midpoint rule with n steps.
double integrate(const reconstruction_filter& f, int n = 200000) {
  double sum = 0.0, h = 2.0 * f.radius / n;
  for (int i = 0; i < n; ++i) sum += filter_weight_1d(f, float(-f.radius + (i + 0.5) * h));
  return sum * h;
}

TEST(reconstruction_filter, names_and_default_radii) {
  EXPECT_EQ(default_filter_radius(filter_kind::box), 0.5f);
  EXPECT_EQ(default_filter_radius(filter_kind::tent), 1.0f);
  EXPECT_EQ(default_filter_radius(filter_kind::gaussian), 1.5f);
  EXPECT_EQ(default_filter_radius(filter_kind::blackman_harris), 2.0f);
  for (filter_kind k : all_kinds) EXPECT_EQ(parse_filter_kind(filter_name(k)), k);
  EXPECT_FALSE(parse_filter_kind("lanczos"));
  EXPECT_FALSE(parse_filter_kind("Box"));
}

TEST(reconstruction_filter, kernel_values_at_centre_and_radius) {
  for (filter_kind k : all_kinds) {
    reconstruction_filter f = default_filter(k);
    EXPECT_FLOAT_EQ(filter_weight_1d(f, 0.0f), k == filter_kind::gaussian ? 1.0f - std::exp(-4.5f) : 1.0f)
        << filter_name(k);
    // Nothing at or beyond the radius (box: the interval is half-open, [-r, r)).
    EXPECT_EQ(filter_weight_1d(f, f.radius), 0.0f) << filter_name(k);
    EXPECT_EQ(filter_weight_1d(f, -f.radius - 1e-3f), 0.0f) << filter_name(k);
    EXPECT_EQ(filter_weight_1d(f, 5.0f), 0.0f) << filter_name(k);
    // Symmetric.
    EXPECT_FLOAT_EQ(filter_weight_1d(f, 0.3f), filter_weight_1d(f, -0.3f)) << filter_name(k);
  }
  reconstruction_filter box = default_filter(filter_kind::box);
  EXPECT_EQ(filter_weight_1d(box, -0.5f), 1.0f);
  // Tent halfway out, Gaussian at one sigma (0.5), Blackman-Harris just inside its ends.
  EXPECT_FLOAT_EQ(filter_weight_1d(default_filter(filter_kind::tent), 0.5f), 0.5f);
  EXPECT_NEAR(filter_weight_1d(default_filter(filter_kind::gaussian), 0.5f), std::exp(-0.5) - std::exp(-4.5),
              1e-6);
  EXPECT_NEAR(filter_weight_1d(default_filter(filter_kind::blackman_harris), -1.99999f), 6e-5, 1e-6);
}

TEST(reconstruction_filter, integrals_match_closed_forms) {
  for (float r : {0.5f, 1.0f, 1.5f, 2.0f, 3.0f}) {
    EXPECT_NEAR(integrate({filter_kind::box, r}), 2.0 * r, 1e-4);
    EXPECT_NEAR(integrate({filter_kind::tent, r}), r, 1e-4);
    // Truncated Gaussian minus its edge value: σ√(2π)·erf(r/(σ√2)) − 2r·exp(−r²/2σ²), σ = r/3.
    double s = r / 3.0;
    EXPECT_NEAR(integrate({filter_kind::gaussian, r}),
                s * std::sqrt(2.0 * M_PI) * std::erf(3.0 / std::sqrt(2.0)) - 2.0 * r * std::exp(-4.5), 1e-4);
    // The cosine terms integrate to 0 over whole periods: a0 · 2r.
    EXPECT_NEAR(integrate({filter_kind::blackman_harris, r}), 0.35875 * 2.0 * r, 1e-4);
  }
}

TEST(reconstruction_filter, integer_shifts_of_the_tent_sum_to_one) {
  // A partition of unity: why the tent of radius 1 reconstructs a constant field exactly.
  reconstruction_filter tent = default_filter(filter_kind::tent);
  for (float d : {0.0f, 0.1f, 0.37f, 0.5f, 0.99f}) {
    double sum = 0.0;
    for (int k = -3; k <= 3; ++k) sum += filter_weight_1d(tent, d + float(k));
    EXPECT_NEAR(sum, 1.0, 1e-6) << d;
  }
}

TEST(splat_film, box_half_pixel_puts_each_sample_in_its_own_pixel_only) {
  reconstruction_filter box = default_filter(filter_kind::box);
  splat_tile t = make_splat_tile(4, 4, 6, 6, filter_reach(box));
  ASSERT_EQ(t.width, 4);
  // Offsets at both ends of [0, 1), where rounding could push a sample into a neighbour.
  for (vec2 o : {vec2(0.0f), vec2(0.99999994f), vec2(1e-9f, 0.5f)}) splat_sample(t, box, 4, 5, o, vec4(1.0f));
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      bool own = t.x0 + x == 4 && t.y0 + y == 5;
      EXPECT_EQ(t.weight[size_t(y) * t.width + x], own ? 3.0f : 0.0f) << x << "," << y;
    }
}

TEST(splat_film, constant_radiance_stays_constant_under_every_filter) {
  for (filter_kind k : all_kinds) {
    reconstruction_filter f = default_filter(k);
    film out(6, 5);
    ordered_tile_merge merge(6, 5, 1);
    splat_tile t = make_splat_tile(0, 0, 6, 5, filter_reach(f));
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 6; ++x)
        for (int s = 0; s < 4; ++s)
          splat_sample(t, f, x, y, vec2(0.25f + 0.5f * (s % 2), 0.25f + 0.5f * (s / 2)),
                       vec4(0.7f, 0.2f, 3.0f, 1.0f));
    merge.add(0, std::move(t));
    merge.resolve(out);
    for (const vec4& c : out.color) {  // within a few float ulps (sums of ~100 weighted terms)
      EXPECT_NEAR(c.r, 0.7f, 1e-6f) << filter_name(k);
      EXPECT_NEAR(c.b, 3.0f, 3e-6f) << filter_name(k);
      EXPECT_NEAR(c.a, 1.0f, 1e-6f) << filter_name(k);
    }
  }
}

// Splats a pseudo-random field through tiles of a 9×7 image, then merges them in `order`.
film merge_in_order(const std::vector<size_t>& order) {
  reconstruction_filter f = default_filter(filter_kind::gaussian);
  std::vector<splat_tile> tiles;
  for (int ty = 0; ty < 7; ty += 4)
    for (int tx = 0; tx < 9; tx += 3) {
      splat_tile t = make_splat_tile(tx, ty, std::min(tx + 3, 9), std::min(ty + 4, 7), filter_reach(f));
      for (int y = ty; y < std::min(ty + 4, 7); ++y)
        for (int x = tx; x < std::min(tx + 3, 9); ++x)
          for (int s = 0; s < 3; ++s) {
            float v = std::sin(float(x * 13 + y * 7 + s * 3)) + 1.5f;
            splat_sample(t, f, x, y, vec2(0.1f + 0.3f * s, 0.8f - 0.25f * s), vec4(v, v * v, 1.0f / v, 1.0f));
          }
      tiles.push_back(std::move(t));
    }
  film out(9, 7);
  ordered_tile_merge merge(9, 7, tiles.size());
  for (size_t i : order) merge.add(i, tiles[i]);
  merge.resolve(out);
  return out;
}

TEST(splat_film, merge_result_does_not_depend_on_arrival_order) {
  film a = merge_in_order({0, 1, 2, 3, 4, 5});
  film b = merge_in_order({5, 3, 4, 1, 0, 2});
  EXPECT_EQ(std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(vec4)), 0);
  // The field is not constant, so a wrong order would show.
  EXPECT_NE(a.color[0].r, a.color[40].r);
}

}  // namespace
}  // namespace kiln
