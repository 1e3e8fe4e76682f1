#include "render/aov_list.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

TEST(aov_list, default_is_beauty_z_n) {
  std::optional<aov_set> aovs = parse_aov_list("beauty,Z,N", nullptr);
  ASSERT_TRUE(aovs);
  EXPECT_TRUE(aovs->beauty && aovs->depth && aovs->normal);
  EXPECT_FALSE(aovs->position || aovs->albedo || aovs->uv || aovs->ids);
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

}  // namespace
}  // namespace kiln
