// Filter kernels against their definitions, and the tile splat buffers' merge order.
#include "render/reconstruction_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "render/splat_film.h"
#include "render/tile_grid.h"

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

TEST(reconstruction_filter, reach_covers_every_pixel_with_weight) {
  EXPECT_EQ(filter_reach(default_filter(filter_kind::box)), 0);
  EXPECT_EQ(filter_reach(default_filter(filter_kind::tent)), 1);
  EXPECT_EQ(filter_reach(default_filter(filter_kind::gaussian)), 1);
  EXPECT_EQ(filter_reach(default_filter(filter_kind::blackman_harris)), 2);
  // A sample anywhere in its pixel has no weight at a centre beyond the reach.
  for (filter_kind k : all_kinds)
    for (float r : {0.3f, 0.5f, 0.75f, 1.0f, 1.5f, 2.0f, 2.6f}) {
      reconstruction_filter f{k, r};
      const float beyond = float(filter_reach(f) + 1);
      for (float o : {0.0f, 0.25f, 0.5f, 0.9375f}) {  // exact in float, so d is not rounded
        EXPECT_EQ(filter_weight_1d(f, (o - 0.5f) - beyond), 0.0f) << filter_name(k) << " " << r;
        EXPECT_EQ(filter_weight_1d(f, (o - 0.5f) + beyond), 0.0f) << filter_name(k) << " " << r;
      }
    }
}

TEST(splat_film, box_half_pixel_puts_each_sample_in_its_own_pixel_only) {
  reconstruction_filter box{filter_kind::box, 0.5f};
  pixel_splat splat(1);  // look one pixel further than box 0.5 reaches
  // Offsets at both ends of [0, 1), where rounding could push a sample into a neighbour.
  for (vec2 o : {vec2(0.0f), vec2(0.99999994f), vec2(1e-9f, 0.5f)}) splat.add(box, o, vec4(1.0f));
  for (size_t k = 0; k < 9; ++k) EXPECT_EQ(splat.weight[k], k == 4 ? 3.0f : 0.0f) << k;
}

// Splats a fixed field of samples over a w×h image rendered in the given tiles, visiting them in
// `reverse` order or not, pixels in raster order inside each tile (as the renderer does).
// Every sample but some fourth ones hits an id in each Cryptomatte layer; the misses are transparent.
film splat_field(const reconstruction_filter& f, int w, int h, std::vector<pixel_rect> tiles, bool reverse,
                 bool constant) {
  const bool layers[matte_layer_count] = {true, true};
  splat_film splats(w, h, tiles, f, layers);
  if (reverse) std::reverse(tiles.begin(), tiles.end());
  pixel_splat splat(splats.reach(), layers);
  aov_set aovs;
  aovs.set(aov::crypto_object);
  aovs.set(aov::crypto_material);
  film out(w, h, aovs);
  tile_sums sums;
  for (const pixel_rect& tile : tiles) {
    splats.begin_tile(sums, tile);
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        splat.clear();
        for (int s = 0; s < 4; ++s) {
          float v = constant ? 0.7f : std::sin(float(x * 13 + y * 7 + s * 3)) + 1.5f;
          vec2 o(0.1f + 0.27f * s, 0.8f - 0.21f * s);
          sample_mattes ids;
          ids.ids[0][object_layer] = uint32_t(x * 3 + y + s) % 5;
          ids.ids[0][material_layer] = uint32_t(x + s) % 3;
          ids.coverage[0] = 1.0f;
          ids.count = 1;
          const bool miss = !constant && s == 3 && (x + y) % 2 == 0;
          splat.add(f, o, miss ? vec4(0.0f) : vec4(v, v * v, 1.0f / v, 1.0f), miss ? nullptr : &ids);
        }
        splats.add(x, y, splat, sums);
      }
    splats.finish_tile(sums, out);
  }
  splats.resolve(out);
  return out;
}

TEST(splat_film, constant_radiance_stays_constant_under_every_filter) {
  for (filter_kind k : all_kinds) {
    film out = splat_field(default_filter(k), 7, 5, make_tiles({0, 0, 7, 5}, 3), false, true);
    for (const vec4& c : out.color) {  // within a few float ulps (sums of up to 100 weighted terms)
      EXPECT_NEAR(c.r, 0.7f, 2e-6f) << filter_name(k);
      EXPECT_NEAR(c.g, 0.49f, 2e-6f) << filter_name(k);
      EXPECT_NEAR(c.a, 1.0f, 2e-6f) << filter_name(k);
    }
  }
}

TEST(splat_film, bytes_do_not_depend_on_tile_size_or_tile_order) {
  for (filter_kind k : all_kinds) {
    reconstruction_filter f = default_filter(k);
    film reference = splat_field(f, 11, 9, make_tiles({0, 0, 11, 9}, 100), false, false);
    for (int tile_size : {1, 2, 3, 4, 5, 8}) {
      for (bool reverse : {false, true}) {
        film other = splat_field(f, 11, 9, make_tiles({0, 0, 11, 9}, tile_size), reverse, false);
        EXPECT_EQ(
            std::memcmp(reference.color.data(), other.color.data(), reference.color.size() * sizeof(vec4)), 0)
            << filter_name(k) << " tiles of " << tile_size << (reverse ? " reversed" : "");
        EXPECT_EQ(reference.crypto_object, other.crypto_object)
            << filter_name(k) << " tiles of " << tile_size;
        EXPECT_EQ(reference.crypto_material, other.crypto_material)
            << filter_name(k) << " tiles of " << tile_size;
      }
    }
    // Coverage is the share of the weight that hit: it sums to alpha in both layers.
    const size_t depth = size_t(reference.aovs.crypto_depth);
    for (size_t p = 0; p < reference.color.size(); ++p)
      for (const std::vector<id_coverage>* layer : {&reference.crypto_object, &reference.crypto_material}) {
        float sum = 0.0f;
        for (size_t r = 0; r < depth; ++r) sum += (*layer)[p * depth + r].coverage;
        EXPECT_NEAR(sum, reference.color[p].a, 1e-6f) << filter_name(k) << " pixel " << p;
      }
    // The field is not constant, so a wrong order would show.
    EXPECT_NE(reference.color[0].r, reference.color[40].r);
  }
}

// The film folds by the tile list it is given, not by a tile size: a grid of uneven columns and
// rows (no single tile size makes it) gives the same bytes as one tile.
TEST(splat_film, folds_by_the_tile_list_for_any_grid_of_columns_and_rows) {
  const int xs[] = {0, 2, 7, 8, 11}, ys[] = {0, 5, 6, 9};
  std::vector<pixel_rect> uneven;
  for (int r = 0; r + 1 < 4; ++r)
    for (int c = 0; c + 1 < 5; ++c) uneven.push_back({xs[c], ys[r], xs[c + 1], ys[r + 1]});
  for (filter_kind k : all_kinds) {
    const reconstruction_filter f = default_filter(k);
    const film reference = splat_field(f, 11, 9, {{0, 0, 11, 9}}, false, false);
    const film other = splat_field(f, 11, 9, uneven, true, false);
    EXPECT_EQ(std::memcmp(reference.color.data(), other.color.data(), reference.color.size() * sizeof(vec4)),
              0)
        << filter_name(k);
    EXPECT_EQ(reference.crypto_object, other.crypto_object) << filter_name(k);
  }
}

TEST(tile_grid, tiles_cover_the_region_row_by_row_with_narrower_last_ones) {
  const std::vector<pixel_rect> tiles = make_tiles({3, 2, 10, 7}, 4);
  const std::vector<pixel_rect> expected = {{3, 2, 7, 6}, {7, 2, 10, 6}, {3, 6, 7, 7}, {7, 6, 10, 7}};
  EXPECT_EQ(tiles, expected);
  EXPECT_EQ(shifted(tiles, -3, -2)[1], (pixel_rect{4, 0, 7, 4}));
}

}  // namespace
}  // namespace kiln
