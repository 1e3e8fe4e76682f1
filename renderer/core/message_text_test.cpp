#include "core/message_text.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

TEST(message_text, short_text_is_shown_whole) {
  EXPECT_EQ(quoted("brick.png"), "'brick.png'");
  EXPECT_EQ(shown("brick.png"), "brick.png");
}

TEST(message_text, long_text_is_cut_with_its_length) {
  const std::string uri(8000000, 'a');
  EXPECT_EQ(quoted(uri), "'" + std::string(max_shown_bytes, 'a') + "...' (8000000 bytes)");
  EXPECT_EQ(shown(uri), std::string(max_shown_bytes, 'a') + "... (8000000 bytes)");
  EXPECT_EQ(shown(std::string(max_shown_bytes, 'b')), std::string(max_shown_bytes, 'b'));
}

TEST(message_text, control_characters_cannot_break_the_line) {
  EXPECT_EQ(quoted("a\nb\tc\x01"), "'a\\nb\\tc\\x01'");
}

TEST(message_text, a_cut_never_splits_a_utf8_sequence) {
  // 199 ASCII bytes and then a two-byte 'é' across the limit: the cut drops the whole 'é'.
  const std::string text = std::string(max_shown_bytes - 1, 'x') + "\xC3\xA9" + "tail";
  EXPECT_EQ(shown(text),
            std::string(max_shown_bytes - 1, 'x') + "... (" + std::to_string(text.size()) + " bytes)");
}

}  // namespace
}  // namespace kiln
