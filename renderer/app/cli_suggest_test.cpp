#include "app/cli_suggest.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

TEST(cli_suggest, edit_distance_counts_a_transposition_as_one_edit) {
  EXPECT_EQ(edit_distance("--widht", "--width"), 1u);  // swapped neighbours
  EXPECT_EQ(edit_distance("rendr", "render"), 1u);     // one missing letter
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}

TEST(cli_suggest, closest_name_takes_only_near_typos) {
  const std::vector<std::string> commands = {"render", "compare", "bench", "stitch", "batch"};
  EXPECT_EQ(closest_name("rendr", commands), "render");
  EXPECT_EQ(closest_name("stich", commands), "stitch");
  EXPECT_EQ(closest_name("bacth", commands), "batch");
  EXPECT_EQ(closest_name("paint", commands), std::nullopt);   // 3+ edits from everything
  EXPECT_EQ(closest_name("-x", {"-o", "-q"}), std::nullopt);  // one edit, but half the word
  EXPECT_EQ(closest_name("--spq", {"--spp", "--up"}), "--spp");
}

}  // namespace
}  // namespace kiln
