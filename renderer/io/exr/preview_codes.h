// The preview's formats and view transform: pure functions that the option checks, the preview
// writer and the contact sheet share. Depends on the standard library only.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace kiln {

// "png" or "jpeg" for a path ending in .png, .jpg or .jpeg (any case); empty otherwise.
std::string preview_format(const std::string& path);

// The preview code value of one linear colour channel: round(255 · srgb(clamp(v · 2^exposure, 0, 1)))
// with the exact piecewise sRGB curve (12.92·v up to 0.0031308, else 1.055·v^(1/2.4) - 0.055).
// NaN maps to 0.
unsigned char preview_code(float linear, double exposure);

// preview_code at one exposure for a whole image, without a pow per value and exactly: the
// smallest float reaching each code is found by bisection on preview_code itself (which rises with
// its input), and each run of floats sharing their top 16 bits knows the codes it spans.
struct preview_code_table {
  std::array<float, 255> thresholds{};  // thresholds[k]: the smallest float of code k + 1 or more
  std::vector<uint8_t> first, last;     // per run of finite positive floats: its first and last code
};
preview_code_table make_preview_code_table(double exposure);

// preview_code(linear, exposure) of the table's exposure.
inline unsigned char preview_code(const preview_code_table& table, float linear) {
  if (!(linear > 0.0f)) return 0;  // zero, negative and NaN
  uint32_t bits = 0;
  static_assert(sizeof bits == sizeof linear);
  std::memcpy(&bits, &linear, sizeof bits);
  const size_t run = bits >> 16;
  if (run >= table.first.size()) return 255;  // +inf
  uint8_t code = table.first[run];
  while (code < table.last[run] && linear >= table.thresholds[code]) ++code;
  return code;
}

}  // namespace kiln
