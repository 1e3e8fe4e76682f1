// The fast paths of texture lookups against the plain ones they replace, bit for bit: level reads
// (SSE2 where the target has it) against a scalar blend of fetch_texel()s, and batched lookups
// (sample_textures, sample_material_textures), which plan once for slots that share an image size,
// sampler, uv and footprint, against the same lookups made one at a time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "scene/mip_pyramid.h"
#include "shade/material_eval.h"
#include "shade/texture_filter.h"
#include "shade/texture_sampling.h"

namespace kiln {
namespace {

bool same_bits(const vec4& a, const vec4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// width × height RGBA of pseudo-random codes (8-bit) or values in [0, 1] (float).
image random_image(int width, int height, bool float_texels, uint32_t seed) {
  std::mt19937 rng(seed);
  image img;
  img.width = width;
  img.height = height;
  const size_t n = size_t(width) * size_t(height) * 4;
  if (float_texels) {
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    img.texels32.resize(n);
    for (float& v : img.texels32) v = value(rng);
  } else {
    img.texels8.resize(n);
    for (uint8_t& v : img.texels8) v = uint8_t(rng() & 255u);
  }
  return img;
}

// The read as the scalar code spells it: four texels blended by glm::mix; linear 8-bit level 0
// blends the codes and scales once, every other format blends fetch_texel()'s linear values.
vec4 scalar_read(const mip_pyramid& p, const level_taps& t) {
  if (t.nearest) return p.texel(t.level, t.x0, t.y0);
  const bool codes = t.level == 0 && !p.level0->texels8.empty() && p.encoding == texel_encoding::linear;
  auto read = [&](int x, int y) {
    if (!codes) return p.texel(t.level, x, y);
    const uint8_t* c = &p.level0->texels8[(size_t(y) * size_t(p.level0->width) + size_t(x)) * 4];
    return vec4(float(c[0]), float(c[1]), float(c[2]), float(c[3]));
  };
  const vec4 top = glm::mix(read(t.x0, t.y0), read(t.x1, t.y0), t.tx);
  const vec4 bottom = glm::mix(read(t.x0, t.y1), read(t.x1, t.y1), t.tx);
  const vec4 blended = glm::mix(top, bottom, t.ty);
  return codes ? blended * (1.0f / 255.0f) : blended;
}

TEST(level_read, matches_the_scalar_blend_bit_for_bit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  int compared = 0;
  for (bool float_texels : {false, true})
    for (texel_encoding encoding : {texel_encoding::linear, texel_encoding::srgb}) {
      const image img = random_image(37, 20, float_texels, 11);
      const mip_pyramid p = build_mip_pyramid(img, encoding);
      for (wrap_mode wrap : {wrap_mode::repeat, wrap_mode::clamp_to_edge, wrap_mode::mirrored_repeat})
        for (filter_mode filter : {filter_mode::linear, filter_mode::nearest}) {
          sampler smp;
          smp.wrap_s = smp.wrap_t = wrap;
          for (int level = 0; level < p.levels(); ++level)
            for (int i = 0; i < 200; ++i) {
              const vec2 uv(coordinate(rng), coordinate(rng));
              const level_taps t = mip_level_taps(p.width(level), p.height(level), level, uv, smp, filter);
              const vec4 fast = read_level_taps(p, t), plain = scalar_read(p, t);
              ASSERT_TRUE(same_bits(fast, plain)) << "level " << level << " uv " << uv.x << "," << uv.y
                                                  << ": " << fast.x << " vs " << plain.x;
              ++compared;
            }
        }
    }
  EXPECT_GT(compared, 10000);
}

bool same_taps(const level_taps& a, const level_taps& b) {
  return a.level == b.level && a.nearest == b.nearest && a.x0 == b.x0 && a.x1 == b.x1 && a.y0 == b.y0 &&
         a.y1 == b.y1 && std::memcmp(&a.tx, &b.tx, sizeof a.tx) == 0 &&
         std::memcmp(&a.ty, &b.ty, sizeof a.ty) == 0;
}

TEST(level_taps, both_levels_at_once_equal_each_level_alone) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-4.0f, 4.0f);
  std::uniform_int_distribution<int> size(1, 300);
  // Edges, exact texel centres and borders, and coordinates past 2^23 (reduced by fmod).
  const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1.0f - 1e-7f, -1e-7f, 3e7f, -3e7f, 8388608.0f};
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const int w = size(rng), h = size(rng);
    const int cw = std::max(1, w / 2), ch = std::max(1, h / 2);
    vec2 uv(coordinate(rng), coordinate(rng));
    if (i % 5 == 0) uv.x = special[size_t(i / 5) % 10];
    if (i % 7 == 0) uv.y = special[size_t(i / 7) % 10];
    if (i % 3 == 0) uv = vec2(float(size(rng) % (w + 1)) / float(w), float(size(rng) % (h + 1)) / float(h));
    for (wrap_mode wrap : {wrap_mode::repeat, wrap_mode::clamp_to_edge, wrap_mode::mirrored_repeat})
      for (filter_mode filter : {filter_mode::linear, filter_mode::nearest}) {
        sampler smp;
        smp.wrap_s = wrap;
        smp.wrap_t = i % 2 ? wrap : wrap_mode::repeat;
        level_taps finer, coarser;
        mip_level_pair_taps(w, h, cw, ch, 2, uv, smp, filter, finer, coarser);
        ASSERT_TRUE(same_taps(finer, mip_level_taps(w, h, 2, uv, smp, filter)))
            << w << "x" << h << " " << uv.x;
        ASSERT_TRUE(same_taps(coarser, mip_level_taps(cw, ch, 3, uv, smp, filter)))
            << cw << "x" << ch << " " << uv.x;
        ++compared;
      }
  }
  EXPECT_EQ(compared, 120000);
}

// Two 64² images and one 32², read through two samplers; materials sample them over footprints
// from magnified to 12:1 minified.
scene batch_scene() {
  scene s;
  s.images.push_back(random_image(64, 64, false, 1));
  s.images.push_back(random_image(64, 64, false, 2));
  s.images.push_back(random_image(32, 32, false, 3));
  s.images.push_back(random_image(64, 64, true, 4));
  sampler trilinear;
  sampler nearest_clamped;
  nearest_clamped.wrap_s = wrap_mode::clamp_to_edge;
  nearest_clamped.min_filter = filter_mode::nearest;
  nearest_clamped.mipmap = mip_mode::nearest;
  for (uint32_t image = 0; image < 4; ++image) s.textures.push_back({image, trilinear});
  s.textures.push_back({1, nearest_clamped});
  material m;
  m.base_color_texture.texture = 0;
  m.metallic_roughness_texture.texture = 1;
  m.emissive_texture.texture = 2;
  m.emissive_factor = vec3(1.0f);
  m.normal_texture.texture = 4;
  m.transmission_texture.texture = 3;
  m.transmission_factor = 0.5f;
  s.materials.push_back(m);
  material transformed = m;  // one slot on another UV transform: planned on its own
  transformed.metallic_roughness_texture.uv_scale = vec2(2.0f, 3.0f);
  transformed.normal_texture.texture = 1;
  s.materials.push_back(transformed);
  return s;
}

uv_footprint random_footprint(std::mt19937& rng) {
  std::uniform_real_distribution<float> width(0.0f, 0.4f), angle(0.0f, 6.2831853f), aspect(1.0f, 12.0f);
  const float w = width(rng) * width(rng), a = angle(rng), r = aspect(rng);
  const vec2 major(std::cos(a), std::sin(a));
  return {major * (w * r), vec2(-major.y, major.x) * w};
}

TEST(texture_batch, equals_the_lookups_one_at_a_time) {
  const scene s = batch_scene();
  const texture_filter filter(s);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-2.0f, 2.0f);
  int minified = 0;
  for (int i = 0; i < 3000; ++i) {
    const vec2 uv(coordinate(rng), coordinate(rng));
    const uv_footprint f = i % 7 == 0 ? uv_footprint{} : random_footprint(rng);
    // Every texture at this uv, two encodings, one lookup at another uv in the middle.
    std::vector<texture_lookup> lookups;
    for (uint32_t t = 0; t < 5; ++t)
      lookups.push_back({t, t % 2 ? texel_encoding::srgb : texel_encoding::linear, uv, f});
    lookups.insert(lookups.begin() + 2, texture_lookup{0, texel_encoding::linear, uv + vec2(0.25f), f});
    lookups.push_back({0, texel_encoding::srgb, uv, f});
    std::vector<vec4> batch(lookups.size());
    sample_textures(s, i % 11 == 0 ? nullptr : &filter, lookups.data(), int(lookups.size()), batch.data());
    for (size_t k = 0; k < lookups.size(); ++k) {
      const texture_lookup& l = lookups[k];
      const vec4 alone =
          sample_texture(s, i % 11 == 0 ? nullptr : &filter, l.texture, l.uv, l.footprint, l.encoding);
      ASSERT_TRUE(same_bits(batch[k], alone)) << "lookup " << i << " slot " << k;
    }
    // Not vacuous: most lookups go through the pyramids, not level 0.
    if (batch[0] != sample_texture(s, nullptr, 0, uv, f, texel_encoding::linear)) ++minified;
  }
  EXPECT_GT(minified, 1500);
}

TEST(texture_batch, material_texels_equal_each_slot_sampled_alone) {
  const scene s = batch_scene();
  const texture_filter filter(s);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> coordinate(-2.0f, 2.0f);
  for (const material& m : s.materials)
    for (int i = 0; i < 1000; ++i) {
      material_inputs in;
      in.uv[0] = vec2(coordinate(rng), coordinate(rng));
      in.uv[1] = in.uv[0];
      in.footprint[0] = in.footprint[1] = random_footprint(rng);
      in.filter = &filter;
      const material_texels t = sample_material_textures(s, m, in, true);
      ASSERT_TRUE(
          same_bits(t.base_color, sample_texture_ref(s, m.base_color_texture, in, texel_encoding::srgb)));
      ASSERT_TRUE(same_bits(t.metallic_roughness,
                            sample_texture_ref(s, m.metallic_roughness_texture, in, texel_encoding::linear)));
      ASSERT_TRUE(same_bits(t.emissive, sample_texture_ref(s, m.emissive_texture, in, texel_encoding::srgb)));
      ASSERT_TRUE(same_bits(t.transmission,
                            sample_texture_ref(s, m.transmission_texture, in, texel_encoding::linear)));
      ASSERT_TRUE(same_bits(t.normal, sample_texture_ref(s, m.normal_texture, in, texel_encoding::linear)));
      const material_point a = evaluate_material(m, in, t), b = evaluate_material(s, m, in);
      ASSERT_EQ(a.base_color, b.base_color);
      ASSERT_EQ(a.roughness, b.roughness);
      ASSERT_EQ(a.emission, b.emission);
      ASSERT_EQ(a.transmission, b.transmission);
    }
}

TEST(texture_batch, skips_slots_shading_does_not_read) {
  scene s = batch_scene();
  material& m = s.materials[0];
  m.emissive_factor = vec3(0.0f);
  m.transmission_factor = 0.0f;
  material_inputs in;
  in.uv[0] = in.uv[1] = vec2(0.3f, 0.7f);
  const material_texels t = sample_material_textures(s, m, in, false);
  EXPECT_EQ(t.emissive, vec4(1.0f));
  EXPECT_EQ(t.transmission, vec4(1.0f));
  EXPECT_EQ(t.normal, vec4(1.0f));
  EXPECT_NE(t.base_color, vec4(1.0f));
}

}  // namespace
}  // namespace kiln
