// Reads an EXR's beauty (R, G, B and A) as float, through OpenEXR, for the 8-bit pictures made of a
// render: the preview and the contact sheet. Only the four channels are read, whatever else the
// file holds. Hides OpenEXR; depends on core only.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace kiln {

// Premultiplied linear R G B A over the data window, row 0 at the top.
struct rgba_image {
  int width = 0, height = 0;
  std::vector<float> pixels;
};

// The R, G, B and A of the first part that has all four (a multi-part file's beauty part), each
// converted exactly from its stored format; nullopt when no part has them. Throws kiln::error
// (input) naming path when the file cannot be opened or its pixels read.
std::optional<rgba_image> read_exr_beauty(const std::string& path);

}  // namespace kiln
