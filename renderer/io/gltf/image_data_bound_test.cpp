// A PNG or lossy WebP whose header declares a size its data is too short to code, or a large
// lossless WebP or GIF coded from almost nothing, is refused from the header, before a decoder
// allocates the image (a header-only 16384x16384 PNG used to cost a gigabyte before its refusal);
// real images coded as tightly as their encoders can still pass.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/gltf/gltf_images.h"
#include "io/gltf/image_header.h"

namespace kiln::gltf_internal {
namespace {

void put_be32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(v >> shift));
}

// A PNG chunk with its CRC, as libpng checks it.
void put_chunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
  put_be32(out, uint32_t(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_be32(out, uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
}

// An 8-bit RGBA PNG of width x height with idat_bytes of image data.
std::vector<uint8_t> png_declaring(uint32_t width, uint32_t height, size_t idat_bytes) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}, ihdr;
  put_be32(ihdr, width);
  put_be32(ihdr, height);
  ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0});
  put_chunk(png, "IHDR", ihdr);
  if (idat_bytes) put_chunk(png, "IDAT", std::vector<uint8_t>(idat_bytes, 0));
  put_chunk(png, "IEND", {});
  return png;
}

// A lossy (VP8) WebP key frame header of width x height followed by vp8_bytes in all.
std::vector<uint8_t> webp_declaring(uint16_t width, uint16_t height, uint32_t vp8_bytes) {
  std::vector<uint8_t> webp = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P', 'V', 'P', '8', ' '};
  for (int shift = 0; shift < 32; shift += 8) webp.push_back(uint8_t(vp8_bytes >> shift));
  std::vector<uint8_t> frame = {
      0, 0, 0, 0x9d, 0x01, 0x2a, uint8_t(width), uint8_t(width >> 8), uint8_t(height), uint8_t(height >> 8)};
  frame.resize(vp8_bytes, 0);
  webp.insert(webp.end(), frame.begin(), frame.end());
  return webp;
}

std::string problem(const std::vector<uint8_t>& bytes) {
  return image_data_problem(bytes.data(), bytes.size(), read_image_header(bytes.data(), bytes.size()));
}

// One solid-colour image written by OpenImageIO's encoder at its tightest, read back as bytes.
std::vector<uint8_t> encoded_solid(const std::string& name, int size, const std::string& compression) {
  // The process id in the name: another checkout's suite may run this test at the same time.
  const std::string path =
      (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)).string();
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(size, size, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("compression", compression);
  const std::vector<uint8_t> pixels(size_t(size) * size * 4, 200);
  EXPECT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) &&
              out->close());
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::filesystem::remove(path);
  return bytes;
}

TEST(image_data_bound, a_png_without_the_data_for_its_size_is_refused_before_decoding) {
  // 100 bytes of image data: libpng would read its header, allocate the gigabyte of rows, then fail.
  const std::vector<uint8_t> short_png = png_declaring(16384, 16384, 100);
  const std::vector<encoded_image> batch = {{short_png.data(), short_png.size(), "big", "/images/0"}};
  try {
    decode_images(batch, "scene.gltf", uint64_t(1) << 30, 1, nullptr);
    FAIL() << "a 16384x16384 PNG of 100 bytes of data decoded";
  } catch (const error& e) {
    EXPECT_STREQ(
        e.what(),
        "scene.gltf: /images/0: PNG header says 16384x16384 texels (1073741824 bytes of pixels), but its "
        "100 bytes of image data (IDAT) can hold at most 169248 (deflate expands at most 1032:1)");
  }
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  EXPECT_LT(usage.ru_maxrss, 512 * 1024) << "peak KiB";    // the image alone is 1 GiB
  EXPECT_NE(problem(png_declaring(16384, 16384, 0)), "");  // header only
  // At the deflate bound it is the decoder's to judge.
  EXPECT_EQ(problem(png_declaring(16384, 16384, 1073741824 / 1032)), "");
}

TEST(image_data_bound, a_lossy_webp_without_the_data_for_its_size_is_refused) {
  EXPECT_EQ(
      problem(webp_declaring(16383, 16383, 32)),
      "WebP header says 16383x16383 texels (1048576 macroblocks, each coded in more than a bit), but its "
      "VP8 data is 32 bytes");
  EXPECT_EQ(problem(webp_declaring(16383, 16383, 1048576 / 8)), "");
}

// A lossless (VP8L) WebP header: signature 0x2f, then width - 1 and height - 1 in 14 bits each.
std::vector<uint8_t> lossless_webp_declaring(uint32_t width, uint32_t height, size_t bytes) {
  std::vector<uint8_t> webp = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P', 'V', 'P', '8', 'L'};
  const uint32_t chunk = uint32_t(bytes - 20), bits = (width - 1) | ((height - 1) << 14);
  for (int shift = 0; shift < 32; shift += 8) webp.push_back(uint8_t(chunk >> shift));
  webp.push_back(0x2f);
  for (int shift = 0; shift < 32; shift += 8) webp.push_back(uint8_t(bits >> shift));
  webp.resize(bytes, 0);
  return webp;
}

// A GIF whose logical screen is width x height, padded to bytes.
std::vector<uint8_t> gif_declaring(uint16_t width, uint16_t height, size_t bytes) {
  std::vector<uint8_t> gif = {'G',
                              'I',
                              'F',
                              '8',
                              '9',
                              'a',
                              uint8_t(width),
                              uint8_t(width >> 8),
                              uint8_t(height),
                              uint8_t(height >> 8)};
  gif.resize(bytes, 0);
  return gif;
}

// Lossless WebP and GIF can code a solid 16383x16383 image in about 32 bytes, which their decoders
// expand to a gigabyte (four such textures took 9.9 GB and 33 s): a large image must bring a byte
// of file for every 4096 bytes of texels. Small placeholders and real images keep passing.
TEST(image_data_bound, a_large_image_from_a_few_bytes_of_lossless_webp_or_gif_is_refused) {
  EXPECT_EQ(problem(lossless_webp_declaring(16383, 16383, 32)),
            "WebP header says 16383x16383 texels (1073610756 bytes as 8-bit RGBA) from 32 bytes of file: "
            "over 4096 bytes of texels a byte, which only a near-uniform image codes (a uniform texture "
            "needs a few texels, or the material's factor alone)");
  EXPECT_NE(problem(gif_declaring(16000, 16000, 64)), "");
  EXPECT_EQ(problem(lossless_webp_declaring(16383, 16383, 1073610756 / 4096 + 1)), "");  // at the bound
  EXPECT_EQ(problem(lossless_webp_declaring(4096, 4096, 32)), "");  // 64 MiB: a placeholder may
  EXPECT_EQ(problem(gif_declaring(1024, 1024, 40)), "");
}

TEST(image_data_bound, solid_images_coded_as_tightly_as_the_encoders_can_pass) {
  const std::vector<uint8_t> png = encoded_solid("kiln_bound_solid.png", 2048, "zip:9");
  ASSERT_GT(png.size(), 8u);
  EXPECT_GT(2048 * 2048 * 4 / png.size(), 500u);  // deflate near its best: the bound is close
  EXPECT_EQ(problem(png), "") << png.size() << " bytes";
  const std::vector<uint8_t> webp = encoded_solid("kiln_bound_solid.webp", 2048, "webp:1");
  ASSERT_GT(webp.size(), 12u);
  EXPECT_EQ(read_image_header(webp.data(), webp.size()).width, 2048u);
  EXPECT_EQ(problem(webp), "") << webp.size() << " bytes";
}

}  // namespace
}  // namespace kiln::gltf_internal
