#include "scene/texture_eval.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

// Each texture input shading reads is in the slot list once, with its colour encoding: a slot
// missing here would go without a mip pyramid and without a UV footprint.
TEST(TextureSlots, ListEveryShadingInputWithItsEncoding) {
  material m;
  EXPECT_FALSE(samples_textures(m));
  const std::pair<texture_ref material::*, texel_encoding> inputs[] = {
      {&material::base_color_texture, texel_encoding::srgb},
      {&material::emissive_texture, texel_encoding::srgb},
      {&material::metallic_roughness_texture, texel_encoding::linear},
      {&material::normal_texture, texel_encoding::linear},
      {&material::transmission_texture, texel_encoding::linear},
      {&material::specular_texture, texel_encoding::linear},
      {&material::specular_color_texture, texel_encoding::srgb},
      {&material::clearcoat_texture, texel_encoding::linear},
      {&material::clearcoat_roughness_texture, texel_encoding::linear},
      {&material::clearcoat_normal_texture, texel_encoding::linear},
      {&material::sheen_color_texture, texel_encoding::srgb},
      {&material::sheen_roughness_texture, texel_encoding::linear},
      {&material::iridescence_texture, texel_encoding::linear},
      {&material::iridescence_thickness_texture, texel_encoding::linear},
      {&material::diffuse_transmission_texture, texel_encoding::linear},
      {&material::diffuse_transmission_color_texture, texel_encoding::srgb},
      {&material::anisotropy_texture, texel_encoding::linear}};
  for (const auto& [member, encoding] : inputs) {
    material one;
    (one.*member).texture = 3;
    EXPECT_TRUE(samples_textures(one));
    int found = 0;
    for (const texture_slot& slot : texture_slots(one))
      if (slot.ref == &(one.*member)) {
        ++found;
        EXPECT_EQ(slot.encoding, encoding);
      }
    EXPECT_EQ(found, 1);
  }
}

TEST(TextureEval, Level0LookupWrapsAndDecodesSrgb) {
  scene s;
  image img;
  img.width = 2;
  img.height = 1;
  img.texels8 = {0, 0, 0, 255, 255, 128, 0, 64};
  s.images.push_back(img);
  texture tex;
  tex.sampling.filter = filter_mode::nearest;
  // u = 1.75 repeats onto the second texel; sRGB decodes RGB but never alpha.
  const vec4 c = sample_texture(s, tex, vec2(1.75f, 0.5f), texel_encoding::srgb);
  EXPECT_FLOAT_EQ(c.r, 1.0f);
  EXPECT_NEAR(c.g, 0.2158605f, 1e-6f);
  EXPECT_FLOAT_EQ(c.a, 64.0f / 255.0f);
  EXPECT_EQ(sample_texture(s, tex, vec2(NAN, 0.5f), texel_encoding::srgb), vec4(1.0f));
}

}  // namespace
}  // namespace kiln
