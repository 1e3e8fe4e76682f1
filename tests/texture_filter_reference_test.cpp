// kiln's own mip-mapped lookups (shade/texture_filter) against OpenImageIO's TextureSystem over the
// same pyramids: the filter kiln used before it read its pyramids itself. Footprints of every
// shape: round ones (one trilinear probe) and ellipses up to 12:1 at any angle (probes along the
// major axis), 1 to 96 texels wide (and thinner than a texel, further down), on a texture with smooth ramps
// and aliasing-prone detail, under every wrap mode. Both compute the same elliptical filter, so they agree to
// float rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "shade/texture_filter.h"
#include "support/oiio_texture_reference.h"

namespace kiln {
namespace {

// 512x512 RGBA8: a smooth gradient, a 16-texel checker, and 2-texel stripes in one corner (detail
// that aliases unless filtered); alpha a slow ramp. (Square: OpenImageIO measures a footprint in
// texels of the image's shorter side, kiln in texels along each axis; they agree on squares.)
image detailed_image() {
  image img;
  img.width = 512;
  img.height = 512;
  img.texels8.resize(size_t(img.width) * size_t(img.height) * 4);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      uint8_t* t = &img.texels8[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
      const bool cell = ((x / 16) + (y / 16)) & 1;
      const bool stripe = x < 128 && y < 64 && (x / 2) % 2 == 0;
      t[0] = uint8_t(cell ? 220 : 30);
      t[1] = uint8_t(stripe ? 255 : (x * 255) / 511);
      t[2] = uint8_t((y * 255) / 511);
      t[3] = uint8_t(128 + (x + y) % 128);
    }
  return img;
}

scene textured_scene(wrap_mode wrap) {
  scene s;
  s.images.push_back(detailed_image());
  texture tex;
  tex.sampling.wrap_s = tex.sampling.wrap_t = wrap;
  s.textures.push_back(tex);
  material m;
  m.base_color_texture.texture = 0;
  m.metallic_roughness_texture.texture = 0;
  s.materials.push_back(m);
  return s;
}

struct difference {
  double mean = 0.0;
  double max = 0.0;
};

// Mean and largest |kiln - OpenImageIO| over every channel of `count` random lookups whose
// footprints are round when max_aspect is 1.
difference compare(const scene& s, texel_encoding encoding, float max_aspect, int count,
                   float min_minor_texels = 1.0f, float max_minor_texels = 96.0f) {
  const texture_filter kiln_filter(s);
  const testing::oiio_texture_reference reference(s);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  difference d;
  for (int i = 0; i < count; ++i) {
    const vec2 uv(unit(random) * 3.0f - 1.0f, unit(random) * 3.0f - 1.0f);  // wraps too
    const float minor =
        min_minor_texels * std::exp2(unit(random) * std::log2(max_minor_texels / min_minor_texels)) / 512.0f;
    const float aspect = 1.0f + (max_aspect - 1.0f) * unit(random);
    const float angle = unit(random) * 3.14159265f;
    const vec2 major_axis = vec2(std::cos(angle), std::sin(angle)) * minor * aspect;
    const vec2 minor_axis = vec2(-std::sin(angle), std::cos(angle)) * minor;
    const uv_footprint f{major_axis, minor_axis};
    const vec4 a = kiln_filter.minified(0, encoding, uv, f);
    const vec4 b = reference.minified(0, encoding, uv, f);
    for (int c = 0; c < 4; ++c) {
      const double e = std::abs(double(a[c]) - double(b[c]));
      d.mean += e / (4.0 * count);
      d.max = std::max(d.max, e);
    }
  }
  return d;
}

TEST(texture_filter_reference, round_footprints_match_openimageio_trilinear) {
  for (wrap_mode wrap : {wrap_mode::repeat, wrap_mode::clamp_to_edge, wrap_mode::mirrored_repeat}) {
    const difference d = compare(textured_scene(wrap), texel_encoding::srgb, 1.0f, 4000);
    std::printf("round, wrap %d: mean %.2e, largest %.2e\n", int(wrap), d.mean, d.max);
    // kiln reduces u to one period before scaling it to texels: u - floor(u) rounds, which moves a
    // read by up to 1e-7 of the image across edges of 255 codes per texel.
    EXPECT_LT(d.mean, 2e-7) << "wrap " << int(wrap);
    EXPECT_LT(d.max, 1e-4) << "wrap " << int(wrap);
  }
}

TEST(texture_filter_reference, anisotropic_footprints_stay_close_to_openimageio) {
  for (wrap_mode wrap : {wrap_mode::repeat, wrap_mode::clamp_to_edge, wrap_mode::mirrored_repeat}) {
    const difference d = compare(textured_scene(wrap), texel_encoding::linear, 12.0f, 4000);
    std::printf("anisotropic, wrap %d: mean %.2e, largest %.2e\n", int(wrap), d.mean, d.max);
    EXPECT_LT(d.mean, 2e-6) << "wrap " << int(wrap);
    EXPECT_LT(d.max, 1e-4) << "wrap " << int(wrap);
  }
}

// Footprints narrower than a texel across (0.1 to 1 texel, up to 12:1): what a 16-spp camera ray
// sees on a 1024² texture, and the regime most minified lookups of such renders are in. The two
// filters agree less closely here (both read level 0 bilinearly, but OpenImageIO spaces and weighs
// the probes of so thin an ellipse its own way): measured mean 1.8e-4, largest 6.0e-2 over the
// stripes. Spacing kiln's probes a texel apart instead (3.4% off ToyCar's 16-spp render) moved
// them to mean 2.8e-3, largest 0.26: this bound is what kept that change out.
TEST(texture_filter_reference, sub_texel_footprints_stay_close_to_openimageio) {
  for (wrap_mode wrap : {wrap_mode::repeat, wrap_mode::clamp_to_edge, wrap_mode::mirrored_repeat}) {
    const difference d = compare(textured_scene(wrap), texel_encoding::linear, 12.0f, 4000, 0.1f, 1.0f);
    std::printf("sub-texel, wrap %d: mean %.2e, largest %.2e\n", int(wrap), d.mean, d.max);
    EXPECT_LT(d.mean, 3e-4) << "wrap " << int(wrap);
    EXPECT_LT(d.max, 0.08) << "wrap " << int(wrap);
  }
}

// A footprint the size of the whole texture reads its average: the 1x1 top level.
TEST(texture_filter_reference, a_footprint_over_the_whole_texture_reads_its_average) {
  const scene s = textured_scene(wrap_mode::repeat);
  const texture_filter f(s);
  dvec4 mean(0.0);
  const image& img = s.images[0];
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) mean += dvec4(fetch_texel(img, x, y, texel_encoding::linear));
  mean /= double(img.width) * img.height;
  const vec4 v =
      f.minified(0, texel_encoding::linear, vec2(0.3f, 0.6f), uv_footprint{vec2(4.0f, 0), vec2(0, 4.0f)});
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(v[c], mean[c], 1e-5) << c;
}

}  // namespace
}  // namespace kiln
