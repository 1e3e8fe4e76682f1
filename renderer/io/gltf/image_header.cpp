#include "io/gltf/image_header.h"

#include <algorithm>
#include <cstring>

namespace kiln::gltf_internal {
namespace {

struct bytes_view {
  const uint8_t* data;
  size_t size;

  bool has(size_t offset, size_t n) const { return offset <= size && n <= size - offset; }
  bool starts_with(const char* magic, size_t offset = 0) const {
    const size_t n = std::strlen(magic);
    return has(offset, n) && std::memcmp(data + offset, magic, n) == 0;
  }
  uint32_t be16(size_t i) const { return (uint32_t(data[i]) << 8) | data[i + 1]; }
  uint32_t be32(size_t i) const { return (be16(i) << 16) | be16(i + 2); }
  uint32_t le16(size_t i) const { return uint32_t(data[i]) | (uint32_t(data[i + 1]) << 8); }
  uint32_t le24(size_t i) const { return le16(i) | (uint32_t(data[i + 2]) << 16); }
  uint32_t le32(size_t i) const { return le16(i) | (le16(i + 2) << 16); }
};

// PNG: the signature, then IHDR's length and type, then width and height (big-endian).
void read_png(const bytes_view& b, image_header& h) {
  if (!b.has(8, 16) || !b.starts_with("IHDR", 12)) return;
  h.width = b.be32(16);
  h.height = b.be32(20);
}

// JPEG: markers from SOI on; the first start-of-frame (SOF0-SOF15 but DHT C4, JPG C8 and DAC CC)
// holds precision, height and width. A scan (SOS) before any frame has no size.
void read_jpeg(const bytes_view& b, image_header& h) {
  size_t pos = 2;
  while (b.has(pos, 4)) {
    if (b.data[pos] != 0xFF) return;
    const uint8_t marker = b.data[pos + 1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {  // markers without a length
      pos += 2;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) return;
    const size_t length = b.be16(pos + 2);
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame) {
      if (length < 7 || !b.has(pos + 4, 5)) return;
      h.height = b.be16(pos + 5);  // 0: set later by a DNL marker, which kiln does not take
      h.width = b.be16(pos + 7);
      return;
    }
    if (length < 2) return;
    pos += 2 + length;
  }
}

// WebP: RIFF, size, WEBP, then the first chunk: VP8 (lossy: key frame start code, then 14-bit
// sizes), VP8L (lossless: signature byte, then 14-bit sizes minus one) or VP8X (extended: 24-bit
// canvas sizes minus one).
void read_webp(const bytes_view& b, image_header& h) {
  if (b.starts_with("VP8 ", 12) && b.has(20, 10) && b.data[23] == 0x9d && b.data[24] == 0x01 &&
      b.data[25] == 0x2a) {
    h.width = b.le16(26) & 0x3fff;
    h.height = b.le16(28) & 0x3fff;
  } else if (b.starts_with("VP8L", 12) && b.has(20, 5) && b.data[20] == 0x2f) {
    const uint32_t bits = b.le32(21);
    h.width = (bits & 0x3fff) + 1;
    h.height = ((bits >> 14) & 0x3fff) + 1;
  } else if (b.starts_with("VP8X", 12) && b.has(24, 6)) {
    h.width = uint64_t(b.le24(24)) + 1;
    h.height = uint64_t(b.le24(27)) + 1;
  }
}

// BMP: the info header's width and height (signed 32-bit; a negative height is a top-down image).
void read_bmp(const bytes_view& b, image_header& h) {
  if (!b.has(14, 12)) return;
  const int32_t width = int32_t(b.le32(18)), height = int32_t(b.le32(22));
  h.width = width < 0 ? uint64_t(-int64_t(width)) : uint64_t(width);
  h.height = height < 0 ? uint64_t(-int64_t(height)) : uint64_t(height);
}

// The bytes of every IDAT chunk of a PNG, as far as its chunk list can be walked.
uint64_t png_image_data_bytes(const bytes_view& b) {
  uint64_t total = 0;
  for (size_t pos = 8; b.has(pos, 12);) {
    const uint64_t length = b.be32(pos);
    if (b.starts_with("IDAT", pos + 4)) total += length;
    if (b.starts_with("IEND", pos + 4) || length > b.size - pos - 12) break;
    pos += 12 + size_t(length);
  }
  return total;
}

// The size of the first chunk named type among a WebP's chunks (after RIFF, size, WEBP), or 0.
uint64_t webp_chunk_bytes(const bytes_view& b, const char* type) {
  for (size_t pos = 12; b.has(pos, 8);) {
    const uint64_t length = b.le32(pos + 4);
    if (b.starts_with(type, pos)) return std::min<uint64_t>(length, b.size - pos - 8);
    if (length > b.size - pos - 8) break;
    pos += 8 + size_t(length) + (length & 1);  // chunks are padded to an even size
  }
  return 0;
}

std::string size_text(const image_header& h) {
  return std::to_string(h.width) + "x" + std::to_string(h.height);
}

}  // namespace

std::string image_data_problem(const uint8_t* data, size_t size, const image_header& h) {
  const bytes_view b{data, size};
  if (h.format == "PNG" && b.has(16, 10)) {
    const uint64_t depth = b.data[24], type = b.data[25];
    const uint64_t channels = type == 0 || type == 3 ? 1 : type == 4 ? 2 : type == 2 ? 3 : type == 6 ? 4 : 0;
    // The pixels' bits alone, without the filter bytes: a lower bound for any interlacing.
    const uint64_t texels = h.width * h.height;  // each at most 2^31 in a PNG
    const uint64_t pixel_bytes = texels > (~uint64_t(0) >> 6) ? ~uint64_t(0) : texels * channels * depth / 8;
    const uint64_t idat = png_image_data_bytes(b);
    constexpr uint64_t deflate_ratio = 1032;      // a 258-byte match in two bits
    if (pixel_bytes / deflate_ratio > idat + 64)  // 64: the zlib header, checksum and block headers
      return "PNG header says " + size_text(h) + " texels (" + std::to_string(pixel_bytes) +
             " bytes of pixels), but its " + std::to_string(idat) +
             " bytes of image data (IDAT) can hold at most " + std::to_string((idat + 64) * deflate_ratio) +
             " (deflate expands at most 1032:1)";
  }
  const uint64_t vp8 = h.format == "WebP" ? webp_chunk_bytes(b, "VP8 ") : 0;
  if (vp8 > 0) {
    const uint64_t macroblocks = ((h.width + 15) / 16) * ((h.height + 15) / 16);
    if (macroblocks > vp8 * 8)
      return "WebP header says " + size_text(h) + " texels (" + std::to_string(macroblocks) +
             " macroblocks, each coded in more than a bit), but its VP8 data is " + std::to_string(vp8) +
             " bytes";
  }
  if (h.format == "PNG" || vp8 > 0) return "";
  // The formats with no such bound (lossless WebP, GIF, arithmetic-coded JPEG) can code a solid
  // image of any size in a few dozen bytes, and their decoders allocate all of it. A large image
  // must bring data in some proportion to its size: among the sample models the highest ratio is
  // 8,300:1 on a 1 MiB placeholder, and no texture above 16 MiB passes 150:1.
  constexpr uint64_t large_image_bytes = uint64_t(64) << 20, max_expansion = 4096;
  const uint64_t texels = h.width * h.height;  // each side at most 2^16 in these formats' headers
  const uint64_t rgba_bytes = texels > (~uint64_t(0) >> 3) ? ~uint64_t(0) : texels * 4;
  if (rgba_bytes > large_image_bytes && rgba_bytes / max_expansion > size)
    return h.format + " header says " + size_text(h) + " texels (" + std::to_string(rgba_bytes) +
           " bytes as 8-bit RGBA) from " + std::to_string(size) +
           " bytes of file: over 4096 bytes of texels a byte, which only a near-uniform image codes "
           "(a uniform texture needs a few texels, or the material's factor alone)";
  return "";
}

image_header read_image_header(const uint8_t* data, size_t size) {
  const bytes_view b{data, size};
  image_header h;
  if (b.starts_with("\x89PNG\r\n\x1a\n")) {
    h.format = "PNG";
    read_png(b, h);
  } else if (b.has(0, 3) && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) {
    h.format = "JPEG";
    read_jpeg(b, h);
  } else if (b.starts_with("RIFF") && b.starts_with("WEBP", 8)) {
    h.format = "WebP";
    read_webp(b, h);
  } else if (b.starts_with("GIF87a") || b.starts_with("GIF89a")) {
    h.format = "GIF";
    if (b.has(6, 4)) {
      h.width = b.le16(6);
      h.height = b.le16(8);
    }
  } else if (b.starts_with("BM")) {
    h.format = "BMP";
    read_bmp(b, h);
  }
  if (h.width == 0 || h.height == 0) h.width = h.height = 0;
  return h;
}

}  // namespace kiln::gltf_internal
