// Image sizes read from the encoded files' own headers, for every format kiln takes, and what a
// cut-short header gives.
#include "io/gltf/image_header.h"

#include <gtest/gtest.h>

#include <vector>

namespace kiln::gltf_internal {
namespace {

image_header read(const std::vector<uint8_t>& bytes) { return read_image_header(bytes.data(), bytes.size()); }

TEST(image_header, png_size_comes_from_ihdr) {
  const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0,    0,    0,    13,
                                    'I',  'H', 'D', 'R', 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x03};
  const image_header h = read(png);
  EXPECT_EQ(h.format, "PNG");
  EXPECT_EQ(h.width, 65536u);
  EXPECT_EQ(h.height, 515u);
  EXPECT_EQ(read(std::vector<uint8_t>(png.begin(), png.end() - 1)).width, 0u);  // cut short
}

TEST(image_header, jpeg_size_comes_from_the_first_frame_after_other_segments) {
  // SOI, an APP0 segment of 4 bytes, fill bytes, then a baseline SOF0 of 640x480.
  const std::vector<uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x04, 0xAA, 0xBB, 0xFF, 0xFF, 0xFF, 0xC0,
                                     0x00, 0x0B, 0x08, 0x01, 0xE0, 0x02, 0x80, 0x01, 0x01, 0x11, 0x00};
  const image_header h = read(jpeg);
  EXPECT_EQ(h.format, "JPEG");
  EXPECT_EQ(h.width, 640u);
  EXPECT_EQ(h.height, 480u);
  // A Huffman table (C4) is not a frame; a scan before any frame leaves the size unknown.
  const std::vector<uint8_t> scan_first = {0xFF, 0xD8, 0xFF, 0xC4, 0x00, 0x02, 0xFF, 0xDA, 0x00, 0x02};
  EXPECT_EQ(read(scan_first).format, "JPEG");
  EXPECT_EQ(read(scan_first).width, 0u);
}

TEST(image_header, webp_sizes_of_lossy_lossless_and_extended_files) {
  std::vector<uint8_t> lossy = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W',  'E',  'B',  'P',  'V',  'P',  '8',
                                ' ', 0,   0,   0,   0, 0, 0, 0, 0x9d, 0x01, 0x2a, 0x20, 0x03, 0x58, 0x02};
  EXPECT_EQ(read(lossy).width, 800u);
  EXPECT_EQ(read(lossy).height, 600u);
  // VP8L: 14-bit width-1 and height-1 packed little-endian after the 0x2f signature.
  const uint32_t bits = (99u) | (49u << 14);
  std::vector<uint8_t> lossless = {'R',
                                   'I',
                                   'F',
                                   'F',
                                   0,
                                   0,
                                   0,
                                   0,
                                   'W',
                                   'E',
                                   'B',
                                   'P',
                                   'V',
                                   'P',
                                   '8',
                                   'L',
                                   0,
                                   0,
                                   0,
                                   0,
                                   0x2f,
                                   uint8_t(bits),
                                   uint8_t(bits >> 8),
                                   uint8_t(bits >> 16),
                                   uint8_t(bits >> 24)};
  EXPECT_EQ(read(lossless).width, 100u);
  EXPECT_EQ(read(lossless).height, 50u);
  std::vector<uint8_t> extended = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E',  'B',  'P', 'V',  'P', '8',
                                   'X', 0,   0,   0,   0, 0, 0, 0, 0,   0xFF, 0x3F, 0,   0x0F, 0,   0};
  EXPECT_EQ(read(extended).width, 16384u);
  EXPECT_EQ(read(extended).height, 16u);
}

TEST(image_header, gif_and_bmp_sizes_and_unknown_data) {
  const std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 0x40, 0x01, 0xF0, 0x00};
  EXPECT_EQ(read(gif).width, 320u);
  EXPECT_EQ(read(gif).height, 240u);
  std::vector<uint8_t> bmp(26, 0);
  bmp[0] = 'B';
  bmp[1] = 'M';
  bmp[18] = 10;                                        // width 10
  bmp[22] = 0xF6, bmp[23] = bmp[24] = bmp[25] = 0xFF;  // height -10: top-down
  EXPECT_EQ(read(bmp).width, 10u);
  EXPECT_EQ(read(bmp).height, 10u);
  EXPECT_EQ(read({'n', 'o', 'p', 'e'}).format, "");
  EXPECT_EQ(read({}).format, "");
}

}  // namespace
}  // namespace kiln::gltf_internal
