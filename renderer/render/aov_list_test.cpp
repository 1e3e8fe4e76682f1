#include "render/aov_list.h"

#include <gtest/gtest.h>

#include "render/aov_table.h"

namespace kiln {
namespace {

TEST(aov_list, default_is_beauty_z_n) {
  std::optional<aov_set> aovs = parse_aov_list("beauty,Z,N", nullptr);
  ASSERT_TRUE(aovs);
  EXPECT_TRUE(aovs->has(aov::beauty) && aovs->has(aov::depth) && aovs->has(aov::normal));
  EXPECT_FALSE(aovs->has(aov::position) || aovs->has(aov::albedo) || aovs->has(aov::uv) ||
               aovs->has(aov::ids));
  EXPECT_EQ(aov_list_name(aov_set{}), "beauty,Z,N");
}

TEST(aov_list, names_come_back_in_channel_order) {
  std::optional<aov_set> aovs = parse_aov_list("id,uv,P,beauty", nullptr);
  ASSERT_TRUE(aovs);
  EXPECT_EQ(aov_list_name(*aovs), "beauty,P,uv,id");
  EXPECT_EQ(aov_list_name(*parse_aov_list("albedo", nullptr)), "albedo");
}

TEST(aov_list, refuses_unknown_repeated_and_empty_names) {
  for (const char* text : {"", ",", "beauty,", "beauty,,Z", "z", "Beauty", "beauty,normal", "Z,Z"}) {
    std::string bad;
    EXPECT_FALSE(parse_aov_list(text, &bad)) << text;
    EXPECT_FALSE(bad.empty()) << text;
  }
}

TEST(aov_list, cryptomatte_is_shorthand_for_both_layers) {
  std::optional<aov_set> both = parse_aov_list("cryptomatte,beauty", nullptr);
  ASSERT_TRUE(both);
  EXPECT_TRUE(both->has(aov::crypto_object) && both->has(aov::crypto_material));
  EXPECT_FALSE(both->has(aov::depth) || both->has(aov::ids));
  EXPECT_EQ(aov_list_name(*both), "beauty,crypto_object,crypto_material");
  std::optional<aov_set> one = parse_aov_list("crypto_material", nullptr);
  ASSERT_TRUE(one);
  EXPECT_FALSE(one->has(aov::crypto_object));
  EXPECT_TRUE(one->has(aov::crypto_material));
  EXPECT_EQ(aov_list_name(*one), "crypto_material");
  for (const char* text : {"cryptomatte,crypto_object", "crypto_material,cryptomatte",
                           "cryptomatte,cryptomatte", "CryptoObject"}) {
    std::string bad;
    EXPECT_FALSE(parse_aov_list(text, &bad)) << text;
    EXPECT_FALSE(bad.empty()) << text;
  }
}

TEST(aov_list, light_split_names) {
  std::optional<aov_set> aovs = parse_aov_list("refraction,beauty,direct", nullptr);
  ASSERT_TRUE(aovs);
  EXPECT_TRUE(aovs->has(aov::direct) && aovs->has(aov::refraction) && wants_light_split(*aovs));
  EXPECT_FALSE(aovs->has(aov::reflection));
  EXPECT_EQ(aov_list_name(*aovs), "beauty,direct,refraction");
  EXPECT_FALSE(wants_light_split(aov_set{}));
}

// The passes come after the light groups in channel order, and each adds its parts to the fold:
// one vec3 each, the shadow mattes three lights to a part.
TEST(aov_list, pass_names_and_part_counts) {
  std::optional<aov_set> aovs =
      parse_aov_list("shadow,specular,N_filtered,beauty,albedo_filtered,diffuse", nullptr);
  ASSERT_TRUE(aovs);
  EXPECT_TRUE(wants_camera_passes(*aovs));
  EXPECT_EQ(aov_list_name(*aovs), "beauty,albedo_filtered,N_filtered,diffuse,specular,shadow");
  // 4 lights + emission + environment: two shadow parts (lights 0-2; light 3 and the environment).
  EXPECT_EQ(beauty_part_count(*aovs, 6), 4 + 2);
  EXPECT_EQ(beauty_part_count(*parse_aov_list("shadow", nullptr), 5), 2);  // 3 lights + the environment
  EXPECT_EQ(beauty_part_count(*parse_aov_list("shadow", nullptr), 4), 1);  // 2 lights + the environment
  EXPECT_EQ(beauty_part_count(*parse_aov_list("shadow,direct,lightgroups", nullptr), 3), 1 + 1 + 3);
  EXPECT_EQ(beauty_part_count(*parse_aov_list("reflection,direct,beauty,Z,N,P", nullptr), 3), 2);
  EXPECT_FALSE(wants_camera_passes(*parse_aov_list("beauty,lightgroups,albedo", nullptr)));
  std::string bad;
  EXPECT_FALSE(parse_aov_list("N_Filtered", &bad));
  EXPECT_EQ(bad, "'N_Filtered'");
}

TEST(aov_list, depth_modes) {
  EXPECT_EQ(parse_depth_mode("distance"), depth_mode::distance);
  EXPECT_EQ(parse_depth_mode("planar"), depth_mode::planar);
  EXPECT_FALSE(parse_depth_mode("Planar"));
}

}  // namespace
}  // namespace kiln
