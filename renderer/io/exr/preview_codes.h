// The preview's formats and view transform: pure functions that the option checks, the preview
// writer and the contact sheet share. Depends on the standard library only.
#pragma once

#include <string>

namespace kiln {

// "png" or "jpeg" for a path ending in .png, .jpg or .jpeg (any case); empty otherwise.
std::string preview_format(const std::string& path);

// The preview code value of one linear colour channel: round(255 · srgb(clamp(v · 2^exposure, 0, 1)))
// with the exact piecewise sRGB curve (12.92·v up to 0.0031308, else 1.055·v^(1/2.4) - 0.055).
// NaN maps to 0.
unsigned char preview_code(float linear, double exposure);

}  // namespace kiln
