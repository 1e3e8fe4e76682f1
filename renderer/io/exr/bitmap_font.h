// A 5x8 pixel font for printable ASCII (capitals 5x7, descenders in the eighth row), drawn for
// kiln, so that a contact sheet can label its images without a font library. Depends on nothing.
#pragma once

#include <cstdint>
#include <string>

namespace kiln {

constexpr int glyph_width = 5;
constexpr int glyph_height = 8;
constexpr int glyph_advance = 6;  // a column of space between letters

// Row `row` (0 at the top) of character c's glyph, bit 4 its leftmost pixel; characters outside
// printable ASCII (32 to 126) draw as '?'.
uint8_t glyph_row(char c, int row);

// text with every character the font lacks as '?': a UTF-8 sequence (one character) becomes one
// '?', so a name in any script keeps its length in characters.
std::string font_text(const std::string& text);

}  // namespace kiln
