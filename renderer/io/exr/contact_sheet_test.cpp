// The contact sheet's grid (columns, box, cells) as its header states it, and the built-in font's
// fallbacks: characters it lacks draw as '?', one per UTF-8 character.
#include "io/exr/contact_sheet.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/exr/bitmap_font.h"

namespace kiln {
namespace {

TEST(contact_sheet, grid_of_small_images_keeps_their_size_and_a_readable_label) {
  const contact_sheet_layout l = contact_sheet_grid(5, {{32, 24}, {32, 24}, {0, 0}, {20, 30}, {32, 24}});
  EXPECT_EQ(l.columns, 3);
  EXPECT_EQ(l.rows, 2);
  EXPECT_EQ(l.box_width, 32);
  EXPECT_EQ(l.box_height, 30);
  EXPECT_EQ(l.text_scale, 1);
  EXPECT_EQ(l.cell_width, 64 + 2 * 4);
  EXPECT_EQ(l.cell_height, 30 + 2 * 4 + 12);
  EXPECT_EQ(l.width, 3 * l.cell_width);
  EXPECT_EQ(l.height, 2 * l.cell_height);
}

TEST(contact_sheet, large_images_shrink_to_the_box_limit_and_double_the_text) {
  const contact_sheet_layout l = contact_sheet_grid(4, {{1920, 1080}, {640, 480}, {0, 0}, {0, 0}});
  EXPECT_EQ(l.columns, 2);
  EXPECT_EQ(l.rows, 2);
  EXPECT_EQ(l.box_width, 256);
  EXPECT_EQ(l.box_height, 144);
  EXPECT_EQ(l.text_scale, 2);
  EXPECT_EQ(l.cell_width, 256 + 8);
  EXPECT_EQ(l.cell_height, 144 + 8 + 24);
}

TEST(contact_sheet, no_image_at_all_still_has_a_box_and_one_cell_one_column) {
  const contact_sheet_layout l = contact_sheet_grid(1, {{0, 0}});
  EXPECT_EQ(l.columns, 1);
  EXPECT_EQ(l.rows, 1);
  EXPECT_EQ(l.box_width, 128);
  EXPECT_EQ(l.box_height, 96);
}

TEST(contact_sheet, other_extensions_are_refused_before_anything_is_read) {
  contact_sheet_cell cell;
  cell.label = "x";
  try {
    write_contact_sheet("sheet.gif", {cell});
    ADD_FAILURE() << "wrote a .gif";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(e.location(), "--contact-sheet");
  }
}

TEST(bitmap_font, characters_it_lacks_read_as_one_question_mark_each) {
  EXPECT_EQ(font_text("shoe_red.0001"), "shoe_red.0001");
  EXPECT_EQ(font_text("caf\xc3\xa9"), "caf?");             // é: two bytes, one character
  EXPECT_EQ(font_text("\xe6\x97\xa5\xe6\x9c\xac"), "??");  // two CJK characters
  EXPECT_EQ(font_text(std::string("a\tb")), "a?b");
  for (int row = 0; row < glyph_height; ++row) EXPECT_EQ(glyph_row('\x7f', row), glyph_row('?', row));
  EXPECT_EQ(glyph_row('I', 0), 0x0e);
  EXPECT_EQ(glyph_row(' ', 3), 0);
}

}  // namespace
}  // namespace kiln
