// A contact sheet: one 8-bit PNG or JPEG holding many renders' beauties in a grid, each with its
// name under it (io/exr/bitmap_font.h) and failed ones marked with a red cross, as asset reviews
// look at a batch. Each EXR's R G B A goes through the preview's view transform (preview_code:
// exposure, clamp, sRGB) over a grey backdrop; the file is encoded by libpng or libjpeg in kiln and
// written atomically. Depends on core and the EXR reader only.
#pragma once

#include <string>
#include <vector>

namespace kiln {

struct contact_sheet_cell {
  std::string exr;        // the render; empty, or a file without R G B A: the cell says "no image"
  std::string label;      // written under the image
  bool failed = false;    // a red cross over the cell and "failed" in place of the image
  double exposure = 0.0;  // stops, as --preview-exposure
};

// The grid in pixels. Every image fits the box (its aspect kept, centred), which is the largest
// width and the largest height among the images, scaled down so neither passes box_limit (128x96
// when no image can be read); a cell is the box, a margin of 4 pixels around it, and a label strip
// of 12 pixels (24 with text at scale 2, used when the box is at least 192 wide) under it, at least
// 64 (128) pixels wide inside its margins. ceil(sqrt(cells)) columns.
struct contact_sheet_layout {
  static constexpr int box_limit = 256;
  static constexpr int margin = 4;
  int columns = 1, rows = 1;
  int box_width = 0, box_height = 0;
  int text_scale = 1;
  int cell_width = 0, cell_height = 0;
  int width = 0, height = 0;  // the whole sheet
};

// The layout of `cells` cells whose images measure image_sizes (width, height; 0 x 0 for a cell
// without one).
contact_sheet_layout contact_sheet_grid(size_t cells, const std::vector<std::pair<int, int>>& image_sizes);

// Writes the sheet of cells to path (.png, .jpg or .jpeg, any case). Throws kiln::error (input)
// for another extension or no cells, (io) when it cannot be written. A cell whose EXR cannot be
// read is drawn without an image rather than failing the sheet.
void write_contact_sheet(const std::string& path, const std::vector<contact_sheet_cell>& cells);

}  // namespace kiln
