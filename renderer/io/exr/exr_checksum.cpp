#include "io/exr/exr_checksum.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineInputPart.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTileDescription.h>
#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cstdio>

#include "core/error.h"
#include "core/memory_budget.h"
#include "io/exr/exr_header_scan.h"

namespace kiln {

const char* const exr_checksum_attribute = "kiln/checksum";

void content_crc::add(const void* bytes, size_t size) {
  const auto* p = static_cast<const Bytef*>(bytes);
  while (size > 0) {  // zlib takes a uInt length
    const uInt n = uInt(std::min<size_t>(size, UINT_MAX));
    value = uint32_t(crc32(value, p, n));
    p += n;
    size -= n;
  }
}

std::string content_crc::text() const {
  char out[16];
  std::snprintf(out, sizeof out, "crc32:%08x", unsigned(value));
  return out;
}

namespace {

std::string box_text(const Imath::Box2i& b) {
  return std::to_string(b.min.x) + "," + std::to_string(b.min.y) + "," + std::to_string(b.max.x) + "," +
         std::to_string(b.max.y);
}

size_t format_bytes(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

size_t pixel_bytes(const std::vector<Imf::Header>& headers) {
  size_t bytes = 0;
  for (const Imf::Header& h : headers)
    for (auto c = h.channels().begin(); c != h.channels().end(); ++c) bytes += format_bytes(c.channel().type);
  return bytes;
}

content_crc layout_crc(const std::vector<Imf::Header>& headers) {
  content_crc crc;
  for (const Imf::Header& h : headers) {
    const std::string text = exr_layout_text(h);
    crc.add(text.data(), text.size());
  }
  return crc;
}

}  // namespace

std::string exr_layout_text(const Imf::Header& h) {
  std::string text = "data " + box_text(h.dataWindow()) + " display " + box_text(h.displayWindow());
  if (h.hasName()) text += " name " + h.name();
  text += " codec " + std::to_string(int(h.compression()));
  if (h.hasTileDescription()) {
    const Imf::TileDescription& t = h.tileDescription();
    text += " tiles " + std::to_string(t.xSize) + "x" + std::to_string(t.ySize) + " " +
            std::to_string(int(t.mode));
  }
  for (auto c = h.channels().begin(); c != h.channels().end(); ++c)
    text += std::string(" ") + c.name() + ":" + std::to_string(int(c.channel().type)) + ":" +
            std::to_string(c.channel().xSampling) + ":" + std::to_string(c.channel().ySampling);
  return text + "\n";
}

std::string flat_exr_checksum(const std::vector<Imf::Header>& headers, const unsigned char* pixels,
                              size_t bytes) {
  content_crc crc = layout_crc(headers);
  crc.add(pixels, bytes);
  return crc.text();
}

std::string flat_exr_checksum(Imf::MultiPartInputFile& file, const std::string& path, memory_budget* budget) {
  std::vector<Imf::Header> headers;
  for (int part = 0; part < file.parts(); ++part) {
    const Imf::Header& h = file.header(part);
    if (h.hasType() && Imf::isDeepData(h.type()))
      throw input_error(path, "part " + std::to_string(part), "a deep part in a flat output");
    if (!headers.empty() && h.dataWindow() != headers.front().dataWindow())
      throw input_error(path, "part " + std::to_string(part), "parts with different data windows");
    headers.push_back(h);
  }
  if (headers.empty()) throw input_error(path, "", "the file has no parts");
  const Imath::Box2i window = headers.front().dataWindow();
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  const size_t pixel = pixel_bytes(headers);
  if (width <= 0 || height <= 0 || pixel == 0 || uint64_t(width) > SIZE_MAX / pixel)
    throw input_error(path, "dataWindow", "no pixels to read, or too many");
  const size_t row = size_t(width) * pixel;
  const int rows = int(std::clamp<int64_t>(int64_t(exr_band_bytes / row), 1, height));
  memory_charge charge(budget);
  charge.add(uint64_t(rows) * row, path, "the resume check's rows of pixels");
  // OpenEXR's own buffers, which the header alone sizes: a chunk of each part (its lines or its tile),
  // compressed and not, and its tables of a few words a line.
  for (const Imf::Header& h : headers) {
    const uint64_t chunk = h.hasTileDescription()
                               ? uint64_t(h.tileDescription().xSize) * h.tileDescription().ySize
                               : uint64_t(exr_lines_per_chunk(int(h.compression()))) * uint64_t(width);
    charge.add(2 * chunk * pixel_bytes({h}) + 16 * uint64_t(height), path, "OpenEXR's decode buffers");
  }
  std::vector<unsigned char> band(size_t(rows) * row);
  content_crc crc = layout_crc(headers);
  for (int64_t y0 = window.min.y; y0 <= window.max.y; y0 += rows) {
    const int y1 = int(std::min<int64_t>(y0 + rows - 1, window.max.y));
    const Imath::Box2i band_window(Imath::V2i(window.min.x, int(y0)), Imath::V2i(window.max.x, y1));
    size_t offset = 0;
    for (int part = 0; part < file.parts(); ++part) {
      Imf::FrameBuffer buffer;
      const Imf::ChannelList& channels = headers[size_t(part)].channels();
      for (auto c = channels.begin(); c != channels.end(); ++c) {
        if (c.channel().xSampling != 1 || c.channel().ySampling != 1)
          throw input_error(path, "part " + std::to_string(part), "a subsampled channel");
        buffer.insert(c.name(),
                      Imf::Slice::Make(c.channel().type, band.data() + offset, band_window, pixel, row));
        offset += format_bytes(c.channel().type);
      }
      Imf::InputPart in(file, part);
      in.setFrameBuffer(buffer);
      in.readPixels(int(y0), y1);
    }
    crc.add(band.data(), size_t(y1 - y0 + 1) * row);
  }
  return crc.text();
}

void add_deep_row(content_crc& crc, const unsigned int* counts, size_t width, const float* samples,
                  size_t floats) {
  crc.add(counts, width * sizeof(unsigned int));
  crc.add(samples, floats * sizeof(float));
}

std::string deep_exr_checksum(Imf::MultiPartInputFile& file, const std::string& path, memory_budget* budget) {
  if (file.parts() != 1 || !file.header(0).hasType() || file.header(0).type() != Imf::DEEPSCANLINE)
    throw input_error(path, "", "not a single-part deep scanline file");
  const Imf::Header& header = file.header(0);
  const Imf::ChannelList& list = header.channels();
  size_t channels = 0;
  for (auto c = list.begin(); c != list.end(); ++c, ++channels)
    if (c.channel().type != Imf::FLOAT || c.channel().xSampling != 1 || c.channel().ySampling != 1)
      throw input_error(path, std::string("channel ") + c.name(), "not a float channel of every pixel");
  if (channels == 0) throw input_error(path, "", "a deep file without channels");
  const Imath::Box2i window = header.dataWindow();
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  if (width <= 0 || window.max.y < window.min.y || uint64_t(width) > (uint64_t(1) << 31))
    throw input_error(path, "dataWindow", "no pixels to read, or too many");
  memory_charge counts_charge(budget);
  // OpenEXR's own buffers first: sample count tables of a line, and tables of a few words a line.
  counts_charge.add(8 * uint64_t(width) + 24 * uint64_t(int64_t(window.max.y) - window.min.y + 1), path,
                    "OpenEXR's deep decode buffers");
  Imf::DeepScanLineInputPart in(file, 0);
  content_crc crc;
  const std::string layout = exr_layout_text(header);
  crc.add(layout.data(), layout.size());
  counts_charge.add(uint64_t(width) * deep_band_rows * (sizeof(unsigned int) + channels * sizeof(char*)),
                    path, "the resume check's deep sample counts");
  std::vector<unsigned int> counts(size_t(width) * deep_band_rows);
  std::vector<std::vector<char*>> first(channels, std::vector<char*>(counts.size()));
  for (int64_t y0 = window.min.y; y0 <= window.max.y; y0 += deep_band_rows) {
    const int y1 = int(std::min<int64_t>(y0 + deep_band_rows - 1, window.max.y));
    const size_t pixels = size_t(width) * size_t(y1 - y0 + 1);
    // OpenEXR addresses pixel (x, y) at base + x·xStride + y·yStride.
    const ptrdiff_t origin = ptrdiff_t(window.min.x) + ptrdiff_t(y0) * ptrdiff_t(width);
    const auto base = [origin](auto* data) {
      return reinterpret_cast<char*>(data) - origin * ptrdiff_t(sizeof(*data));
    };
    // The slices point at counts and at the per-pixel pointer arrays, which are filled once the
    // counts are known: the frame buffer is set once for both reads.
    Imf::DeepFrameBuffer buffer;
    buffer.insertSampleCountSlice(Imf::Slice(Imf::UINT, base(counts.data()), sizeof(unsigned int),
                                             sizeof(unsigned int) * size_t(width)));
    size_t c = 0;
    for (auto ch = list.begin(); ch != list.end(); ++ch, ++c)
      buffer.insert(ch.name(), Imf::DeepSlice(Imf::FLOAT, base(first[c].data()), sizeof(char*),
                                              sizeof(char*) * size_t(width), channels * sizeof(float)));
    in.setFrameBuffer(buffer);
    in.readPixelSampleCounts(int(y0), y1);
    uint64_t total = 0;  // at most 2^35 pixels of 2^32 samples: no overflow
    for (size_t i = 0; i < pixels; ++i) total += counts[i];
    if (total > (uint64_t(1) << 48) / channels)
      throw input_error(path, "rows " + std::to_string(y0) + "-" + std::to_string(y1),
                        "impossibly many samples");
    memory_charge samples_charge(budget);
    samples_charge.add(total * channels * sizeof(float), path, "the resume check's deep samples");
    std::vector<float> samples(size_t(total) * channels);
    for (c = 0; c < channels; ++c) {
      size_t next = 0;
      for (size_t i = 0; i < pixels; ++i) {
        first[c][i] = counts[i] ? reinterpret_cast<char*>(samples.data() + next * channels + c) : nullptr;
        next += counts[i];
      }
    }
    in.readPixels(int(y0), y1);
    // Row by row: counts, then the row's samples (contiguous in samples).
    size_t sample = 0;
    for (int y = int(y0); y <= y1; ++y) {
      const unsigned int* row = counts.data() + size_t(y - y0) * size_t(width);
      size_t in_row = 0;
      for (int64_t x = 0; x < width; ++x) in_row += row[x];
      add_deep_row(crc, row, size_t(width), samples.data() + sample * channels, in_row * channels);
      sample += in_row;
    }
  }
  return crc.text();
}

}  // namespace kiln
