// kiln's own PNG and JPEG decoding (io/image_codecs/direct_decode.h) against the image codecs
// module (OpenImageIO), which decoded every glTF image before: the same size and the same bytes
// for every PNG and JPEG of the shared sample assets and for images written here in each PNG
// colour type, and nothing (the module's turn) for what it leaves to the module.
#include "io/image_codecs/direct_decode.h"

#include <gtest/gtest.h>

// clang-format off
#include <cstdio>  // jpeglib.h needs FILE declared first
#include <jpeglib.h>
// clang-format on

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "io/image_codecs/codecs_loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

constexpr uint64_t no_limit = uint64_t(1) << 40;

std::vector<uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

image module_decode(const std::vector<uint8_t>& bytes) {
  return load_image_codecs("the test needs")
      .decode(bytes.data(), bytes.size(), "", "test", "/images/0", no_limit);
}

// Decodes bytes both ways; true when kiln decoded them itself (then both agree exactly).
bool expect_same_as_module(const std::vector<uint8_t>& bytes, const std::string& what) {
  const std::optional<image> direct = decode_directly(bytes.data(), bytes.size(), no_limit);
  if (!direct) return false;
  const image reference = module_decode(bytes);
  EXPECT_EQ(direct->width, reference.width) << what;
  EXPECT_EQ(direct->height, reference.height) << what;
  EXPECT_TRUE(direct->texels32.empty()) << what;
  EXPECT_EQ(reference.texels32.size(), 0u) << what << ": the module decoded it to float";
  EXPECT_TRUE(direct->texels8 == reference.texels8) << what << ": the texels differ";
  return true;
}

TEST(direct_decode, every_sample_png_and_jpeg_decodes_as_the_module_decodes_it) {
  const fs::path assets = KILN_SHARED_ASSETS;
  if (!fs::is_directory(assets)) GTEST_SKIP() << "no shared assets at " << assets;
  int png = 0, jpeg = 0, left = 0;
  for (const auto& entry : fs::recursive_directory_iterator(assets)) {
    const std::string ext = entry.path().extension().string();
    const bool is_png = ext == ".png", is_jpeg = ext == ".jpg" || ext == ".jpeg";
    if (!entry.is_regular_file() || (!is_png && !is_jpeg) || entry.file_size() > (64u << 20)) continue;
    if (entry.path().string().find("/invalid/") != std::string::npos) continue;
    if (expect_same_as_module(read_bytes(entry.path()), entry.path().string()))
      ++(is_png ? png : jpeg);
    else
      ++left;
  }
  EXPECT_GT(png, 20);
  EXPECT_GT(jpeg, 5);
  std::cout << png << " PNG and " << jpeg << " JPEG decoded alike; " << left << " left to the module\n";
}

// A 4x4 PNG of colour type `type` at `depth` bits (palette: 4 entries, two with tRNS alpha),
// assembled byte by byte (one stored deflate block) so that every colour type is covered.
std::vector<uint8_t> tiny_png(int type, bool transparency, int depth = 8);

TEST(direct_decode, each_png_colour_type_decodes_as_the_module_decodes_it) {
  for (int type : {0, 2, 3, 4, 6})
    for (bool transparency : {false, true}) {
      if (transparency && (type == 4 || type == 6)) continue;  // tRNS only without an alpha channel
      const std::string what = "colour type " + std::to_string(type) + (transparency ? " with tRNS" : "");
      EXPECT_TRUE(expect_same_as_module(tiny_png(type, transparency), what)) << what;
    }
  for (int depth : {1, 2, 4}) {
    const std::string what = "grey at " + std::to_string(depth) + " bits";
    EXPECT_TRUE(expect_same_as_module(tiny_png(0, false, depth), what)) << what;
  }
}

TEST(direct_decode, leaves_to_the_module_what_it_does_not_decode) {
  // 16-bit PNG: float texels, the module's.
  EXPECT_FALSE(decode_directly(tiny_png(2, false, 16).data(), tiny_png(2, false, 16).size(), no_limit));
  // Past the texel limit: the module refuses it with its message.
  const std::vector<uint8_t> png = tiny_png(2, false);
  EXPECT_FALSE(decode_directly(png.data(), png.size(), 3));
  EXPECT_TRUE(decode_directly(png.data(), png.size(), 64));
  // Truncated data: nothing, whatever is cut.
  for (size_t keep = 0; keep < png.size(); ++keep)
    EXPECT_FALSE(decode_directly(png.data(), keep, no_limit)) << keep;
  // Not PNG or JPEG at all.
  const std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0};
  EXPECT_FALSE(decode_directly(gif.data(), gif.size(), no_limit));
}

// A 37x23 JPEG written here with libjpeg (grey or YCbCr colour, baseline or progressive), so that
// the JPEG path is held to the module without the shared assets too.
std::vector<uint8_t> small_jpeg(bool colour, bool progressive) {
  jpeg_compress_struct cinfo;
  jpeg_error_mgr errors;
  cinfo.err = jpeg_std_error(&errors);
  jpeg_create_compress(&cinfo);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&cinfo, &buffer, &size);
  cinfo.image_width = 37;
  cinfo.image_height = 23;
  cinfo.input_components = colour ? 3 : 1;
  cinfo.in_color_space = colour ? JCS_RGB : JCS_GRAYSCALE;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, 85, TRUE);
  if (progressive) jpeg_simple_progression(&cinfo);
  jpeg_start_compress(&cinfo, TRUE);
  std::vector<uint8_t> row(size_t(cinfo.image_width) * size_t(cinfo.input_components));
  while (cinfo.next_scanline < cinfo.image_height) {
    for (size_t i = 0; i < row.size(); ++i) row[i] = uint8_t((i * 29 + cinfo.next_scanline * 53) & 0xFF);
    JSAMPROW pointer = row.data();
    jpeg_write_scanlines(&cinfo, &pointer, 1);
  }
  jpeg_finish_compress(&cinfo);
  std::vector<uint8_t> out(buffer, buffer + size);
  jpeg_destroy_compress(&cinfo);
  std::free(buffer);
  return out;
}

TEST(direct_decode, jpegs_written_here_decode_as_the_module_decodes_them) {
  for (bool colour : {false, true})
    for (bool progressive : {false, true}) {
      const std::string what =
          std::string(colour ? "colour" : "grey") + (progressive ? " progressive" : " baseline");
      const std::vector<uint8_t> jpeg = small_jpeg(colour, progressive);
      EXPECT_TRUE(expect_same_as_module(jpeg, what)) << what;
      EXPECT_FALSE(decode_directly(jpeg.data(), jpeg.size() / 2, no_limit)) << what << ", cut in half";
    }
}

TEST(direct_decode, a_truncated_jpeg_is_left_to_the_module) {
  const fs::path assets = KILN_SHARED_ASSETS;
  if (!fs::is_directory(assets)) GTEST_SKIP() << "no shared assets at " << assets;
  for (const auto& entry : fs::recursive_directory_iterator(assets)) {
    if (entry.path().extension() != ".jpg" || entry.path().string().find("/invalid/") != std::string::npos)
      continue;
    const std::vector<uint8_t> bytes = read_bytes(entry.path());
    ASSERT_TRUE(decode_directly(bytes.data(), bytes.size(), no_limit)) << entry.path();
    for (size_t keep : {size_t(2), bytes.size() / 3, bytes.size() / 2, bytes.size() - 2})
      EXPECT_FALSE(decode_directly(bytes.data(), keep, no_limit)) << entry.path() << " cut at " << keep;
    return;
  }
  GTEST_SKIP() << "no JPEG among the shared assets";
}

// Corrupted data (bytes overwritten at random places, deterministic) is decoded or refused, never
// read past (the sanitizer build runs this): a decoded image always has the texels it claims.
void expect_corruptions_survive(const std::vector<uint8_t>& original, const std::string& what) {
  uint32_t state = 12345u;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  int decoded = 0, refused = 0;
  for (int variant = 0; variant < 300; ++variant) {
    std::vector<uint8_t> bytes = original;
    const int flips = 1 + int(next() % 8);
    for (int k = 0; k < flips; ++k) bytes[next() % bytes.size()] = uint8_t(next() >> 24);
    const std::optional<image> out = decode_directly(bytes.data(), bytes.size(), 1u << 24);
    if (!out) {
      ++refused;
      continue;
    }
    ++decoded;
    ASSERT_GT(out->width, 0) << what;
    ASSERT_GT(out->height, 0) << what;
    ASSERT_EQ(out->texels8.size(), size_t(out->width) * size_t(out->height) * 4) << what;
  }
  EXPECT_GT(refused, 0) << what;  // some corruptions are caught (CRCs, markers)
  EXPECT_EQ(decoded + refused, 300) << what;
}

TEST(direct_decode, corrupted_images_are_decoded_or_refused_never_overrun) {
  expect_corruptions_survive(tiny_png(3, true), "palette PNG");
  expect_corruptions_survive(tiny_png(2, false), "RGB PNG");
  expect_corruptions_survive(small_jpeg(true, false), "baseline JPEG");
  expect_corruptions_survive(small_jpeg(true, true), "progressive JPEG");
  const fs::path assets = KILN_SHARED_ASSETS;
  if (!fs::is_directory(assets)) return;
  int jpegs = 0;
  for (const auto& entry : fs::recursive_directory_iterator(assets)) {
    if (entry.path().extension() != ".jpg" || entry.file_size() > (512u << 10) ||
        entry.path().string().find("/invalid/") != std::string::npos)
      continue;
    expect_corruptions_survive(read_bytes(entry.path()), entry.path().string());
    if (++jpegs == 2) break;
  }
}

// ---- tiny PNGs -----------------------------------------------------------------------------------

uint32_t crc32_of(const uint8_t* data, size_t n, uint32_t crc = 0xFFFFFFFFu) {
  for (size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc;
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(uint8_t(v >> s));
}

void chunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
  put32(out, uint32_t(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, crc32_of(out.data() + start, out.size() - start) ^ 0xFFFFFFFFu);
}

// A zlib stream holding raw in one stored block.
std::vector<uint8_t> stored_zlib(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> z = {0x78,
                            0x01,
                            0x01,
                            uint8_t(raw.size()),
                            uint8_t(raw.size() >> 8),
                            uint8_t(~raw.size()),
                            uint8_t(~raw.size() >> 8)};
  z.insert(z.end(), raw.begin(), raw.end());
  uint32_t a = 1, b = 0;
  for (uint8_t c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  put32(z, (b << 16) | a);
  return z;
}

std::vector<uint8_t> tiny_png(int type, bool transparency, int depth) {
  constexpr int size = 4;
  const int channels = type == 0 ? 1 : type == 2 ? 3 : type == 3 ? 1 : type == 4 ? 2 : 4;
  const int bits = channels * depth;
  const size_t row_bytes = size_t((size * bits + 7) / 8);
  std::vector<uint8_t> raw;
  for (int y = 0; y < size; ++y) {
    raw.push_back(0);  // filter: none
    for (size_t i = 0; i < row_bytes; ++i) raw.push_back(uint8_t((37 * y + 61 * int(i) + 11 * type) & 0xFF));
    if (type == 3)  // palette indices within its 4 entries
      for (size_t i = raw.size() - row_bytes; i < raw.size(); ++i) raw[i] &= 0x03;
  }
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> header;
  put32(header, size);
  put32(header, size);
  header.insert(header.end(), {uint8_t(depth), uint8_t(type), 0, 0, 0});
  chunk(png, "IHDR", header);
  if (type == 3) chunk(png, "PLTE", {255, 0, 0, 0, 255, 0, 0, 0, 255, 90, 180, 30});
  if (transparency) {
    if (type == 3) chunk(png, "tRNS", {0, 128});
    if (type == 0) chunk(png, "tRNS", {0, 37});
    if (type == 2) chunk(png, "tRNS", {0, 11, 0, 61, 0, 122});
  }
  chunk(png, "IDAT", stored_zlib(raw));
  chunk(png, "IEND", {});
  return png;
}

}  // namespace
}  // namespace kiln
