// The preview writer without the image codecs module: an EXR's beauty (found in whichever part
// holds it, in half) becomes the documented codes in a PNG that libpng decodes back exactly; a
// write that is cancelled or cannot be made leaves nothing, earlier files kept, with one line; and
// a preview counts as complete only when it is whole and of the right size.
#include "io/exr/preview_writer.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/error.h"
#include "io/image_codecs/direct_decode.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir(const std::string& name) { return testing::scratch_folder("preview_writer_" + name); }

std::vector<unsigned char> bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The documented view transform, written out independently of kiln's code.
int srgb_code(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return int(std::lround(255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055)));
}

// Four pixels, premultiplied: opaque (0.25, 0.5, 0.75); half-covered (0.1, 0.2, 0.3) over
// alpha 0.5; empty; and a NaN red over a colour brighter than 1.
const float beauty[4][4] = {{0.25f, 0.5f, 0.75f, 1.0f},
                            {0.1f, 0.2f, 0.3f, 0.5f},
                            {0.0f, 0.0f, 0.0f, 0.0f},
                            {std::numeric_limits<float>::quiet_NaN(), 4.0f, 0.0625f, 1.0f}};

// A two-part EXR of 4x1 pixels: part 0 holds only Z, part 1 the beauty in half, as kiln's
// --multipart writes a depth layer beside the rgba part.
void write_two_part_exr(const std::string& path) {
  Imf::Header depth(4, 1), rgba(4, 1);
  depth.setName("depth");
  depth.setType(Imf::SCANLINEIMAGE);
  depth.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  rgba.setName("rgba");
  rgba.setType(Imf::SCANLINEIMAGE);
  for (const char* c : {"R", "G", "B", "A"}) rgba.channels().insert(c, Imf::Channel(Imf::HALF));
  Imf::MultiPartOutputFile file(path.c_str(), std::vector<Imf::Header>{depth, rgba}.data(), 2);
  std::vector<float> z(4, 1.0f);
  Imf::FrameBuffer depth_buffer;
  depth_buffer.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float), 0));
  Imf::OutputPart depth_part(file, 0);
  depth_part.setFrameBuffer(depth_buffer);
  depth_part.writePixels(1);
  std::vector<Imath::half> h(16);
  for (size_t i = 0; i < 16; ++i) h[i] = Imath::half(beauty[i / 4][i % 4]);
  Imf::FrameBuffer rgba_buffer;
  const char* names[4] = {"R", "G", "B", "A"};
  for (size_t c = 0; c < 4; ++c)
    rgba_buffer.insert(
        names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(h.data() + c), 4 * sizeof(Imath::half), 0));
  Imf::OutputPart rgba_part(file, 1);
  rgba_part.setFrameBuffer(rgba_buffer);
  rgba_part.writePixels(1);
}

TEST(preview_writer, png_holds_the_straight_srgb_codes_of_the_beauty_part) {
  const fs::path dir = scratch_dir("codes");
  write_two_part_exr((dir / "two.exr").string());
  write_preview((dir / "two.exr").string(), (dir / "two.png").string(), 0.0);
  const std::vector<unsigned char> png = bytes_of(dir / "two.png");
  const std::optional<image> decoded = decode_directly(png.data(), png.size(), 4);
  ASSERT_TRUE(decoded);
  ASSERT_EQ(decoded->width, 4);
  ASSERT_EQ(decoded->height, 1);
  const int expected[4][4] = {
      {137, 188, 225, 255},  // 0.25, 0.5 and 0.75 are exact in half
      {srgb_code(double(Imath::half(0.1f)) / 0.5), srgb_code(double(Imath::half(0.2f)) / 0.5),
       srgb_code(double(Imath::half(0.3f)) / 0.5), 128},  // colour divided by alpha; 127.5 rounds up
      {0, 0, 0, 0},
      {0, 255, srgb_code(0.0625), 255}};  // NaN is 0, 4 clamps to 1
  EXPECT_EQ(srgb_code(0.25), 137);
  for (size_t i = 0; i < 4; ++i)
    for (size_t c = 0; c < 4; ++c)
      EXPECT_EQ(int(decoded->texels8[i * 4 + c]), expected[i][c]) << "pixel " << i << " channel " << c;
  EXPECT_TRUE(preview_complete((dir / "two.png").string(), 4, 1));
}

// The table gives preview_code's code for every float: checked at each code's first float and
// the float before it, and at a million floats spread over the whole range, for several exposures.
// (The whole of [0, 1] at exposure 0, every float, agreed when the table was written.)
TEST(preview_writer, the_code_table_is_preview_code_exactly) {
  const auto float_of = [](uint32_t bits) {
    float f = 0.0f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  };
  for (const double exposure : {0.0, 1.5, -2.0, 7.25, -40.0}) {
    const preview_code_table table = make_preview_code_table(exposure);
    size_t differ = 0;
    const auto check = [&](float v) { differ += preview_code(table, v) != preview_code(v, exposure); };
    for (const float t : table.thresholds) {
      check(t);
      check(std::nextafter(t, 0.0f));
    }
    for (uint64_t bits = 0; bits <= 0xFFFFFFFFu; bits += 4099) check(float_of(uint32_t(bits)));
    for (const float v : {0.0f, -0.0f, -1.0f, std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min()})
      check(v);
    EXPECT_EQ(differ, 0u) << "exposure " << exposure;
  }
  const preview_code_table table = make_preview_code_table(0.0);
  EXPECT_EQ(preview_code(table, 0.25f), 137);
  EXPECT_EQ(preview_code(table, 1.0f), 255);
  EXPECT_EQ(preview_code(table, std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(preview_writer, an_exr_without_a_beauty_is_refused_naming_it) {
  const fs::path dir = scratch_dir("no_beauty");
  Imf::Header header(2, 2);
  header.setType(Imf::SCANLINEIMAGE);
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  std::vector<float> z(4, 1.0f);
  {
    Imf::MultiPartOutputFile file((dir / "z.exr").c_str(), &header, 1);
    Imf::FrameBuffer buffer;
    buffer.insert(
        "Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float), 2 * sizeof(float)));
    Imf::OutputPart part(file, 0);
    part.setFrameBuffer(buffer);
    part.writePixels(2);
  }
  try {
    write_preview((dir / "z.exr").string(), (dir / "z.png").string(), 0.0);
    FAIL() << "no error";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(e.file(), (dir / "z.exr").string());
    EXPECT_NE(std::string(e.what()).find("no R G B A"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "z.png"));
}

TEST(preview_writer, a_cancelled_or_impossible_write_leaves_nothing_and_says_so_on_one_line) {
  const fs::path dir = scratch_dir("failures");
  const std::vector<unsigned char> codes(6 * 4 * 3, 100);
  std::ofstream(dir / "kept.jpg") << "earlier";
  const std::atomic<bool> cancel{true};
  try {
    write_preview_image((dir / "kept.jpg").string(), 6, 4, 3, codes, &cancel);
    FAIL() << "no error";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::interrupted) << e.what();
  }
  const std::vector<unsigned char> kept = bytes_of(dir / "kept.jpg");
  EXPECT_EQ(std::string(kept.begin(), kept.end()), "earlier");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1)
      << "a temporary file is left";

  const std::string missing = (dir / "no_such_folder" / "x.png").string();
  try {
    write_preview_image(missing, 6, 4, 3, codes);
    FAIL() << "no error";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::io);
    const std::string line = e.what();
    EXPECT_EQ(line.rfind(missing + ": cannot write png: ", 0), 0u) << line;
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  }
}

TEST(preview_writer, only_a_whole_preview_of_the_right_size_and_format_is_complete) {
  const fs::path dir = scratch_dir("complete");
  const std::vector<unsigned char> codes(8 * 6 * 4, 200);
  for (const std::string name : {"p.png", "p.jpg"}) {
    const fs::path path = dir / name;
    write_preview_image(path.string(), 8, 6, 4, codes);
    EXPECT_TRUE(preview_complete(path.string(), 8, 6)) << name;
    EXPECT_FALSE(preview_complete(path.string(), 8, 7)) << name;
    std::vector<unsigned char> bytes = bytes_of(path);
    bytes.resize(bytes.size() - 3);
    std::ofstream(dir / ("cut_" + name), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    EXPECT_FALSE(preview_complete((dir / ("cut_" + name)).string(), 8, 6)) << name;
  }
  fs::copy_file(dir / "p.png", dir / "png_named.jpg");
  EXPECT_FALSE(preview_complete((dir / "png_named.jpg").string(), 8, 6));
  EXPECT_FALSE(preview_complete((dir / "absent.png").string(), 8, 6));
}

}  // namespace
}  // namespace kiln
