#include "io/exr/contact_sheet.h"

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartInputFile.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <optional>

#include "core/error.h"
#include "io/exr/bitmap_font.h"
#include "io/exr/exr_beauty.h"
#include "io/exr/preview_codes.h"
#include "io/exr/preview_writer.h"

namespace kiln {

namespace {

using colour = std::array<unsigned char, 3>;

constexpr colour sheet_background = {24, 24, 24};
constexpr colour empty_box = {48, 48, 48};
constexpr colour failed_box = {56, 16, 16};
constexpr colour cross_red = {230, 32, 32};
constexpr colour label_grey = {220, 220, 220};
constexpr colour failed_label = {255, 96, 96};
constexpr colour note_white = {255, 255, 255};
// What shows through transparent pixels: a dark grey (linear), so light and dark assets both stand out.
constexpr float backdrop = 0.05f;

// The data window's size from the header alone (0 x 0 when the file cannot be read).
std::pair<int, int> exr_size(const std::string& path) {
  if (path.empty()) return {0, 0};
  try {
    Imf::MultiPartInputFile file(path.c_str());
    const Imath::Box2i window = file.header(0).dataWindow();
    return {window.max.x - window.min.x + 1, window.max.y - window.min.y + 1};
  } catch (const std::exception&) {
    return {0, 0};
  }
}

// The EXR's R G B A over its data window; nullopt when it has none or cannot be read.
std::optional<rgba_image> read_beauty(const std::string& path) {
  if (path.empty()) return std::nullopt;
  try {
    return read_exr_beauty(path);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// For each of `out` samples spanning the same extent as `in`: the input samples it overlaps and
// their share of it (an area average when shrinking, the nearest sample when enlarging).
std::vector<std::vector<std::pair<int, float>>> area_weights(int in, int out) {
  std::vector<std::vector<std::pair<int, float>>> weights(static_cast<size_t>(out));
  for (int o = 0; o < out; ++o) {
    const double x0 = double(o) * in / out, x1 = double(o + 1) * in / out;
    double sum = 0.0;
    for (int i = int(std::floor(x0)); i < int(std::ceil(x1)) && i < in; ++i) {
      const double w = std::min(x1, double(i + 1)) - std::max(x0, double(i));
      if (w <= 0.0) continue;
      weights[size_t(o)].emplace_back(i, float(w));
      sum += w;
    }
    for (auto& entry : weights[size_t(o)]) entry.second = float(entry.second / sum);
  }
  return weights;
}

rgba_image resized(const rgba_image& src, int width, int height) {
  const auto across = area_weights(src.width, width), down = area_weights(src.height, height);
  std::vector<float> rows(size_t(width) * size_t(src.height) * 4, 0.0f);
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < width; ++x)
      for (const auto& [i, w] : across[size_t(x)])
        for (size_t c = 0; c < 4; ++c)
          rows[(size_t(y) * size_t(width) + size_t(x)) * 4 + c] +=
              w * src.pixels[(size_t(y) * size_t(src.width) + size_t(i)) * 4 + c];
  rgba_image out;
  out.width = width;
  out.height = height;
  out.pixels.assign(size_t(width) * size_t(height) * 4, 0.0f);
  for (int y = 0; y < height; ++y)
    for (const auto& [j, w] : down[size_t(y)])
      for (int x = 0; x < width; ++x)
        for (size_t c = 0; c < 4; ++c)
          out.pixels[(size_t(y) * size_t(width) + size_t(x)) * 4 + c] +=
              w * rows[(size_t(j) * size_t(width) + size_t(x)) * 4 + c];
  return out;
}

// The sheet's 8-bit R G B, row 0 at the top.
struct canvas {
  int width = 0, height = 0;
  std::vector<unsigned char> codes;

  void put(int x, int y, const colour& c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::copy(c.begin(), c.end(), codes.begin() + long((size_t(y) * size_t(width) + size_t(x)) * 3));
  }
  void fill(int x0, int y0, int x1, int y1, const colour& c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) put(x, y, c);
  }
  // text (font_text already) with its top-left corner at (x, y), each font pixel scale x scale.
  void text(int x, int y, const std::string& line, int scale, const colour& c) {
    for (size_t k = 0; k < line.size(); ++k)
      for (int row = 0; row < glyph_height; ++row) {
        const uint8_t bits = glyph_row(line[k], row);
        for (int column = 0; column < glyph_width; ++column)
          if (bits & (0x10 >> column))
            fill(x + (int(k) * glyph_advance + column) * scale, y + row * scale,
                 x + (int(k) * glyph_advance + column + 1) * scale, y + (row + 1) * scale, c);
      }
  }
};

int text_width(const std::string& line, int scale) {
  return line.empty() ? 0 : (int(line.size()) * glyph_advance - 1) * scale;
}

// The label cut to `characters`, keeping its end (where a sequence's frame number is) after "..".
std::string fitted(const std::string& label, int characters) {
  if (int(label.size()) <= characters) return label;
  if (characters <= 2) return label.substr(label.size() - size_t(std::max(characters, 0)));
  return ".." + label.substr(label.size() - size_t(characters - 2));
}

// A note such as "failed" centred on the box, on a black plate so it reads over anything.
void centred_note(canvas& sheet, int x0, int y0, int width, int height, const std::string& note, int scale,
                  const colour& c) {
  const int w = text_width(note, scale), h = glyph_height * scale;
  const int x = x0 + (width - w) / 2, y = y0 + (height - h) / 2;
  sheet.fill(x - 2 * scale, y - 2 * scale, x + w + 2 * scale, y + h + 2 * scale, {0, 0, 0});
  sheet.text(x, y, note, scale, c);
}

// Both diagonals of the box, `thickness` pixels wide.
void cross(canvas& sheet, int x0, int y0, int width, int height, double thickness) {
  const double length = std::hypot(double(width), double(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double down = std::abs(py * width - px * height) / length;
      const double up = std::abs((height - py) * width - px * height) / length;
      if (std::min(down, up) <= 0.5 * thickness) sheet.put(x0 + x, y0 + y, cross_red);
    }
}

// The render composited over the backdrop into the box at (x, y), its aspect kept and centred.
void place_image(canvas& sheet, const rgba_image& image, int x, int y, int box_width, int box_height,
                 double exposure) {
  const double scale = std::min(double(box_width) / image.width, double(box_height) / image.height);
  const int width = std::clamp(int(std::lround(image.width * scale)), 1, box_width);
  const int height = std::clamp(int(std::lround(image.height * scale)), 1, box_height);
  const rgba_image small = resized(image, width, height);
  const float gain = float(std::exp2(exposure));
  const int left = x + (box_width - width) / 2, top = y + (box_height - height) / 2;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float* p = &small.pixels[(size_t(j) * size_t(width) + size_t(i)) * 4];
      const float alpha = std::isnan(p[3]) ? 0.0f : std::clamp(p[3], 0.0f, 1.0f);
      colour c;
      for (size_t k = 0; k < 3; ++k) c[k] = preview_code(p[k] * gain + (1.0f - alpha) * backdrop, 0.0);
      sheet.put(left + i, top + j, c);
    }
}

}  // namespace

contact_sheet_layout contact_sheet_grid(size_t cells, const std::vector<std::pair<int, int>>& image_sizes) {
  contact_sheet_layout l;
  while (size_t(l.columns) * size_t(l.columns) < cells) ++l.columns;
  l.rows = std::max<int>(1, int((cells + size_t(l.columns) - 1) / size_t(l.columns)));
  for (const auto& [w, h] : image_sizes) {
    if (w <= 0 || h <= 0) continue;
    l.box_width = std::max(l.box_width, w);
    l.box_height = std::max(l.box_height, h);
  }
  if (l.box_width == 0) {
    l.box_width = 128;
    l.box_height = 96;
  } else if (std::max(l.box_width, l.box_height) > contact_sheet_layout::box_limit) {
    const double f = double(contact_sheet_layout::box_limit) / std::max(l.box_width, l.box_height);
    l.box_width = std::max(1, int(std::lround(l.box_width * f)));
    l.box_height = std::max(1, int(std::lround(l.box_height * f)));
  }
  l.text_scale = l.box_width >= 192 ? 2 : 1;
  const int label = 12 * l.text_scale;
  l.cell_width = std::max(l.box_width, 64 * l.text_scale) + 2 * contact_sheet_layout::margin;
  l.cell_height = l.box_height + 2 * contact_sheet_layout::margin + label;
  l.width = l.columns * l.cell_width;
  l.height = l.rows * l.cell_height;
  return l;
}

void write_contact_sheet(const std::string& path, const std::vector<contact_sheet_cell>& cells) {
  if (preview_format(path).empty())
    throw input_error("", "--contact-sheet",
                      "a contact sheet must end in .png, .jpg or .jpeg, got '" + path + "'");
  if (cells.empty()) throw input_error(path, "--contact-sheet", "no images to put on the sheet");
  std::vector<std::pair<int, int>> sizes;
  for (const contact_sheet_cell& cell : cells)
    sizes.push_back(cell.failed ? std::pair{0, 0} : exr_size(cell.exr));
  const contact_sheet_layout l = contact_sheet_grid(cells.size(), sizes);
  const int s = l.text_scale, m = contact_sheet_layout::margin;
  canvas sheet;
  sheet.width = l.width;
  sheet.height = l.height;
  sheet.codes.resize(size_t(l.width) * size_t(l.height) * 3);
  sheet.fill(0, 0, l.width, l.height, sheet_background);
  for (size_t index = 0; index < cells.size(); ++index) {
    const contact_sheet_cell& cell = cells[index];
    const int cx = int(index % size_t(l.columns)) * l.cell_width,
              cy = int(index / size_t(l.columns)) * l.cell_height;
    const int bx = cx + (l.cell_width - l.box_width) / 2, by = cy + m;
    if (cell.failed) {
      sheet.fill(bx, by, bx + l.box_width, by + l.box_height, failed_box);
      cross(sheet, bx, by, l.box_width, l.box_height,
            std::max(2.0, std::min(l.box_width, l.box_height) / 16.0));
      centred_note(sheet, bx, by, l.box_width, l.box_height, "failed", s, note_white);
    } else if (const std::optional<rgba_image> image = read_beauty(cell.exr)) {
      place_image(sheet, *image, bx, by, l.box_width, l.box_height, cell.exposure);
    } else {
      sheet.fill(bx, by, bx + l.box_width, by + l.box_height, empty_box);
      centred_note(sheet, bx, by, l.box_width, l.box_height, "no image", s, label_grey);
    }
    const int characters = (l.cell_width - 2 * m + s) / (glyph_advance * s);
    const std::string label = fitted(font_text(cell.label), characters);
    sheet.text(cx + (l.cell_width - text_width(label, s)) / 2, by + l.box_height + m + 2 * s, label, s,
               cell.failed ? failed_label : label_grey);
  }
  write_preview_image(path, l.width, l.height, 3, sheet.codes);
}

}  // namespace kiln
