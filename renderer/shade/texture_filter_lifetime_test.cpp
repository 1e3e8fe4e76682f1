// Texture filters made and dropped one after another in one process, as `kiln batch` does for each
// asset, each sampled from TBB's worker threads. Every filter must answer its lookups, and the same
// lookups alike. (When the filter was OpenImageIO's, a second filter met the freed per-thread state
// of the first one on the worker threads: an assertion, a crash, or a use after free.)
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <vector>

#include "shade/texture_filter.h"

namespace kiln {
namespace {

// A 512x512 RGBA8 image of hashed texels (no two neighbours alike, so every mip level differs),
// read through a trilinear mip-mapped sampler from a material's base colour.
scene textured_scene() {
  scene s;
  image img;
  img.width = img.height = 512;
  img.texels8.resize(size_t(img.width) * size_t(img.height) * 4);
  uint32_t h = 2166136261u;
  for (uint8_t& t : img.texels8) t = uint8_t((h = (h ^ 0x9e3779b9u) * 16777619u) >> 24);
  s.images.push_back(std::move(img));
  s.textures.push_back(texture{});
  material m;
  m.base_color_texture.texture = 0;
  s.materials.push_back(m);
  return s;
}

// 4096 lookups over the whole texture at several footprints, spread over the worker threads.
std::vector<vec4> sample_everywhere(const texture_filter& filter) {
  std::vector<vec4> out(4096);
  tbb::parallel_for(size_t(0), out.size(), [&](size_t i) {
    const vec2 uv((float(i % 64) + 0.5f) / 64.0f, (float(i / 64) + 0.5f) / 64.0f);
    const float width = float(1 << (i % 7)) / 512.0f;  // 1 to 64 texels: levels 0 to 6
    out[i] = filter.minified(0, texel_encoding::srgb, uv, uv_footprint{vec2(width, 0.0f), vec2(0.0f, width)});
  });
  return out;
}

TEST(texture_filter_lifetime, filters_made_one_after_another_answer_their_lookups) {
  const scene s = textured_scene();
  std::vector<vec4> first;
  for (int round = 0; round < 12; ++round) {
    const texture_filter filter(s);
    const std::vector<vec4> values = sample_everywhere(filter);
    if (round == 0) first = values;
    EXPECT_TRUE(values == first) << "round " << round;
    size_t untextured = 0;
    for (const vec4& v : values) untextured += v == vec4(1.0f);  // what a failed lookup returns
    EXPECT_LT(untextured, values.size() / 100) << "round " << round;
  }
}

// Lookups at one hit reuse the previous lookup's filter plan when it fits; texture 1 is half the
// size of texture 0, so reading it over texture 0's footprint must plan afresh (another level),
// and back again. Each interleaved lookup must equal the same lookup after an unrelated one.
TEST(texture_filter_lifetime, lookups_over_one_footprint_at_two_image_sizes_stay_independent) {
  scene s = textured_scene();
  image half;
  half.width = half.height = 256;
  half.texels8.resize(size_t(half.width) * size_t(half.height) * 4);
  for (size_t i = 0; i < half.texels8.size(); ++i) half.texels8[i] = uint8_t((i * 2654435761u) >> 13);
  s.images.push_back(std::move(half));
  texture second;
  second.image = 1;
  s.textures.push_back(second);
  s.materials[0].emissive_texture.texture = 1;
  const texture_filter filter(s);
  const uv_footprint unrelated{vec2(0.5f, 0.0f), vec2(0.0f, 0.01f)};
  for (const uv_footprint& f :
       {uv_footprint{vec2(8.0f / 512.0f, 0.0f), vec2(0.0f, 8.0f / 512.0f)},
        uv_footprint{vec2(40.0f / 512.0f, 10.0f / 512.0f), vec2(-1.0f / 512.0f, 4.0f / 512.0f)}}) {
    const vec2 uv(0.37f, 0.61f);
    vec4 fresh[2];
    for (uint32_t t = 0; t < 2; ++t) {
      filter.minified(1 - t, texel_encoding::srgb, uv, unrelated);
      fresh[t] = filter.minified(t, texel_encoding::srgb, uv, f);
    }
    EXPECT_NE(fresh[0], fresh[1]);
    EXPECT_EQ(filter.minified(0, texel_encoding::srgb, uv, f), fresh[0]);
    EXPECT_EQ(filter.minified(1, texel_encoding::srgb, uv, f), fresh[1]);
    EXPECT_EQ(filter.minified(0, texel_encoding::srgb, uv, f), fresh[0]);
  }
}

// A loaded scene's next pose moves its images into new places; a filter rebinds to them and
// answers as a filter made afresh. It refuses (and keeps its pyramids on the old images) when an
// image was copied or decoded again (another buffer), when a material reads the images otherwise,
// or for another scene.
TEST(texture_filter_lifetime, a_filter_rebinds_to_its_images_moved_and_to_nothing_else) {
  scene s = textured_scene();
  texture_filter filter(s);
  const std::vector<vec4> before = sample_everywhere(filter);

  std::vector<image> moved(std::make_move_iterator(s.images.begin()),
                           std::make_move_iterator(s.images.end()));
  s.images = std::move(moved);  // new image objects, the same texel buffer
  ASSERT_TRUE(filter.rebind(s));
  EXPECT_EQ(&filter.pyramid(0, texel_encoding::srgb).level0->texels8, &s.images[0].texels8);
  EXPECT_TRUE(sample_everywhere(filter) == before);
  EXPECT_TRUE(sample_everywhere(texture_filter(s)) == before);

  const image copy = s.images[0];
  image original = std::move(s.images[0]);
  s.images[0] = copy;  // the same texels in another buffer: decoded again, say
  EXPECT_FALSE(filter.rebind(s));
  s.images[0] = std::move(original);
  EXPECT_TRUE(filter.rebind(s));

  s.textures[0].sampling.mipmap = mip_mode::none;  // read without its pyramid now
  EXPECT_FALSE(filter.rebind(s));
  s.textures[0].sampling.mipmap = mip_mode::linear;
  EXPECT_TRUE(filter.rebind(s));

  scene other = textured_scene();
  other.images = std::move(s.images);
  EXPECT_FALSE(filter.rebind(other));
}

}  // namespace
}  // namespace kiln
