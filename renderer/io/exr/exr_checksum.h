// The content checksum every EXR kiln writes records as kiln/checksum, so `kiln batch --resume` can
// tell an intact output from a damaged one: CRC-32 (zlib) of the file's layout, then of its pixels
// exactly as a reader gets them back (after the codec, for lossy ones). Inside io/exr only.
#pragma once

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartInputFile.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kiln {

class memory_budget;

// The header attribute holding the checksum, "crc32:" and eight hex digits.
extern const char* const exr_checksum_attribute;

// A running CRC-32 of bytes given in order.
struct content_crc {
  uint32_t value = 0;
  void add(const void* bytes, size_t size);
  std::string text() const;  // "crc32:0123abcd"
};

// What the checksum covers of a part besides its pixels: windows, name, codec, tiling and channels
// (name, format, sampling): an edited display window or channel name changes the checksum.
std::string exr_layout_text(const Imf::Header& header);

// Rows of a flat file read at a time: about this many bytes of pixels, at least one row.
constexpr size_t exr_band_bytes = size_t(16) << 20;

// The checksum of a flat file's layout and every pixel of every part, read band by band (all parts
// interleaved per pixel, row-major: the layout write_exr hands to OpenEXR). Throws kiln::error (input)
// naming path for a deep part, parts with different data windows, a band over budget, and
// OpenEXR's exceptions for a damaged file.
std::string flat_exr_checksum(Imf::MultiPartInputFile& file, const std::string& path, memory_budget* budget);

// The same for pixels in memory, laid out as above, of a file whose parts have headers.
std::string flat_exr_checksum(const std::vector<Imf::Header>& headers, const unsigned char* pixels,
                              size_t bytes);

// Rows of a deep file read at a time.
constexpr int deep_band_rows = 16;

// The checksum of a deep scanline file (one part, every channel float): its layout, then row by row
// the row's sample counts (uint32) and its samples, pixel by pixel, each sample's channels in
// channel-list order. Each band's samples are charged to budget before they are read. Throws as
// flat_exr_checksum does, and for a file that is not one deep scanline part of float channels.
std::string deep_exr_checksum(Imf::MultiPartInputFile& file, const std::string& path, memory_budget* budget);

// Adds one row of a deep file as deep_exr_checksum reads it: counts[width], then the row's samples
// (floats of them, each sample's channels in channel-list order).
void add_deep_row(content_crc& crc, const unsigned int* counts, size_t width, const float* samples,
                  size_t floats);

}  // namespace kiln
