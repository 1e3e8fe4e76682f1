// kiln's own PNG and JPEG encoder against the OpenImageIO 2.4 writer the preview used before: for
// the same codes the same JPEG bytes, and a PNG with the same chunks around its image data that
// libpng decodes to exactly the codes; and refusals of sizes the formats cannot hold.
#include "io/image_codecs/direct_encode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "io/image_codecs/direct_decode.h"

namespace kiln {
namespace {

// Codes with every value and no structure for a filter or predictor to exploit, and an edge of
// flat colour, as a render has both.
std::vector<unsigned char> test_codes(int width, int height, int channels) {
  std::vector<unsigned char> codes(size_t(width) * size_t(height) * size_t(channels));
  std::mt19937 random(7);
  for (size_t i = 0; i < codes.size(); ++i)
    codes[i] = (i / size_t(channels)) % size_t(width) < size_t(width) / 2 ? (unsigned char)(random() & 0xFF)
                                                                          : (unsigned char)(40 + i % 3);
  return codes;
}

// What the preview's OpenImageIO writer made of the codes: the spec and attributes it set.
std::vector<unsigned char> oiio_encoded(const std::string& format, int width, int height, int channels,
                                        const std::vector<unsigned char>& codes) {
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  if (channels == 4) {
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (format == "jpeg") spec.attribute("Compression", "jpeg:95");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create(format);
  EXPECT_TRUE(out);
  if (!out) return bytes;
  EXPECT_TRUE(out->set_ioproxy(&memory) && out->open("x." + format, spec) &&
              out->write_image(OIIO::TypeDesc::UINT8, codes.data()));
  EXPECT_TRUE(out->close());
  return bytes;
}

// A PNG's chunks but its image data (IDAT), each as type and contents.
std::vector<std::string> chunks_around_the_pixels(const std::vector<unsigned char>& png) {
  std::vector<std::string> chunks;
  for (size_t at = 8; at + 12 <= png.size();) {
    const size_t length =
        (size_t(png[at]) << 24) | (size_t(png[at + 1]) << 16) | (size_t(png[at + 2]) << 8) | png[at + 3];
    const std::string chunk(png.begin() + long(at) + 4, png.begin() + long(at + 8 + length));
    if (chunk.compare(0, 4, "IDAT") != 0) chunks.push_back(chunk);
    at += 12 + length;
  }
  return chunks;
}

TEST(direct_encode, png_holds_openimageio_s_chunks_and_decodes_to_the_codes) {
  for (int channels : {3, 4}) {
    const int width = 67, height = 41;  // rows of odd length, and more than one IDAT chunk at 4 channels
    const std::vector<unsigned char> codes = test_codes(width, height, channels);
    std::vector<unsigned char> png;
    ASSERT_EQ(encode_png(width, height, channels, codes.data(), png), "");
    const std::vector<std::string> chunks = chunks_around_the_pixels(png);
    EXPECT_EQ(chunks, chunks_around_the_pixels(oiio_encoded("png", width, height, channels, codes)));
    ASSERT_EQ(chunks.size(), 7u);  // IHDR gAMA sRGB cHRM oFFs tEXt IEND
    EXPECT_EQ(chunks[2], std::string("sRGB\3", 5));
    EXPECT_EQ(chunks[5], std::string("tEXtoiio:ColorSpace\0sRGB", 24));

    const std::optional<image> decoded = decode_directly(png.data(), png.size(), uint64_t(width) * height);
    ASSERT_TRUE(decoded);
    ASSERT_EQ(decoded->width, width);
    ASSERT_EQ(decoded->height, height);
    size_t differ = 0;
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
      for (size_t c = 0; c < 4; ++c) {
        const unsigned char expected = c < size_t(channels) ? codes[i * size_t(channels) + c] : 255;
        differ += decoded->texels8[i * 4 + c] != expected;
      }
    EXPECT_EQ(differ, 0u) << channels << " channels";
  }
}

TEST(direct_encode, jpeg_is_openimageio_s_file) {
  const int width = 53, height = 37;  // partial 16x16 blocks at the right and bottom
  const std::vector<unsigned char> codes = test_codes(width, height, 3);
  std::vector<unsigned char> jpeg;
  ASSERT_EQ(encode_jpeg(width, height, codes.data(), jpeg), "");
  EXPECT_EQ(jpeg, oiio_encoded("jpeg", width, height, 3, codes));
  // The Exif block's ColorSpace says sRGB (tag 0xA001, SHORT, 1).
  const unsigned char colour_space[] = {0x01, 0xA0, 3, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_NE(std::search(jpeg.begin(), jpeg.end(), colour_space, colour_space + sizeof colour_space),
            jpeg.end());
  const std::optional<image> decoded = decode_directly(jpeg.data(), jpeg.size(), uint64_t(width) * height);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->width, width);
}

TEST(direct_encode, sizes_the_formats_cannot_hold_are_refused_with_a_reason) {
  const std::vector<unsigned char> codes(16 * 3, 0);
  std::vector<unsigned char> out;
  EXPECT_NE(encode_png(0, 4, 3, codes.data(), out), "");
  EXPECT_NE(encode_png(4, 4, 2, codes.data(), out), "");
  EXPECT_NE(encode_jpeg(4, -1, codes.data(), out), "");
  const std::string too_wide = encode_jpeg(70000, 1, codes.data(), out);  // past JPEG's 65500
  EXPECT_NE(too_wide.find("70000x1"), std::string::npos) << too_wide;
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace kiln
