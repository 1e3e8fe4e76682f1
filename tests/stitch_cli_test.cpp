// `kiln render --band i/N` and `kiln stitch` end to end: the bands of the demo scene stitched
// together are the full render, channel for channel and format for format (single-part scanline,
// and multi-part tiled, part for part); inputs that overlap or
// leave a gap, and malformed --band requests, are refused with exit code 2 and one line.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/exr_header.h"
#include "support/float_exr.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::command_result;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

// Arguments that render the demo scene at 64x48 with every output the test compares into path.
std::vector<std::string> render_arguments(const std::string& path, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"render", demo_scene, "-o",    path, "--width", "64",           "--height",
                                   "48",     "-q",       "--spp", "2",  "--aovs",  "beauty,Z,N,id"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// Renders into dir/name and returns the path; a failed render fails the test.
std::string render(const std::string& dir, const std::string& name, const std::vector<std::string>& extra) {
  const command_result result = run_kiln(render_arguments(dir + "/" + name, extra));
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return dir + "/" + name;
}

using image = testing::float_exr;
const auto read = testing::read_float_exr;

TEST(stitch_cli, bands_cover_the_frame_rows_exactly_once) {
  const std::string dir = scratch_folder("stitch_bands");
  std::vector<int> covered(48, 0);
  for (int i = 0; i < 5; ++i) {
    image band = read(render(dir, "band.exr", {"--band", std::to_string(i) + "/5"}));
    EXPECT_EQ(band.spec.x, 0);
    EXPECT_EQ(band.spec.width, 64);
    EXPECT_EQ(band.spec.full_width, 64);
    EXPECT_EQ(band.spec.full_height, 48);
    EXPECT_GE(band.spec.height, 9);  // 48 rows in 5 bands: 9 or 10 each
    EXPECT_LE(band.spec.height, 10);
    for (int y = band.spec.y; y < band.spec.y + band.spec.height; ++y) ++covered[size_t(y)];
  }
  for (int y = 0; y < 48; ++y) EXPECT_EQ(covered[size_t(y)], 1) << "row " << y;
}

TEST(stitch_cli, stitched_bands_equal_the_full_render) {
  const std::string dir = scratch_folder("stitch_equal");
  const std::string full = render(dir, "full.exr", {});
  std::vector<std::string> args = {"stitch", dir + "/stitched.exr"};
  for (int i = 0; i < 3; ++i)
    args.push_back(render(dir, "band" + std::to_string(i) + ".exr", {"--band", std::to_string(i) + "/3"}));
  auto result = run_kiln(args);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;

  image a = read(full), b = read(dir + "/stitched.exr");
  // Data window, then display window: both the full frame.
  auto windows = [](const OIIO::ImageSpec& s) {
    return std::vector<int>{s.x, s.y, s.width, s.height, s.full_x, s.full_y, s.full_width, s.full_height};
  };
  EXPECT_EQ(windows(b.spec), (std::vector<int>{0, 0, 64, 48, 0, 0, 64, 48}));
  EXPECT_EQ(windows(b.spec), windows(a.spec));
  ASSERT_EQ(a.spec.channelnames, b.spec.channelnames);
  EXPECT_EQ(a.spec.channelnames.size(), 11u);  // RGBA, Z, N.XYZ, three ids
  for (int c = 0; c < a.spec.nchannels; ++c)
    EXPECT_EQ(a.spec.channelformat(c), b.spec.channelformat(c)) << a.spec.channelnames[size_t(c)];
  EXPECT_EQ(b.spec.channelformat(a.spec.channelindex("R")), OIIO::TypeDesc::HALF);
  EXPECT_EQ(b.spec.channelformat(a.spec.channelindex("Z")), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(b.spec.get_string_attribute("kiln/aovs"), "beauty,Z,N,id");  // the first band's header
  // The stitched frame carries the full render's settings hash (a band's own names its --band),
  // so `kiln batch --resume` takes it for that render's output.
  EXPECT_EQ(b.spec.get_string_attribute("kiln/settings_hash"),
            a.spec.get_string_attribute("kiln/settings_hash"));
  EXPECT_NE(read(dir + "/band0.exr").spec.get_string_attribute("kiln/settings_hash"),
            a.spec.get_string_attribute("kiln/settings_hash"));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  // Bytes, not values: NaN-free, but background Z is +inf and the comparison must be exact.
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
  size_t differing = 0;
  for (size_t k = 0; k < a.pixels.size(); ++k)
    differing += std::memcmp(&a.pixels[k], &b.pixels[k], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u);
}

// Every part of a file in its native formats, and what names each part and its tiling.
struct stored_parts {
  std::vector<std::string> names;
  std::vector<int> tile_widths;
  std::vector<std::vector<std::string>> channels;
  std::vector<std::vector<unsigned char>> bytes;
};

stored_parts read_parts(const std::string& path) {
  stored_parts out;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  for (int s = 0; in && in->seek_subimage(s, 0); ++s) {
    const OIIO::ImageSpec spec = in->spec();
    out.names.push_back(spec.get_string_attribute("oiio:subimagename"));
    out.tile_widths.push_back(spec.tile_width);
    out.channels.push_back(spec.channelnames);
    out.bytes.emplace_back(spec.image_bytes(true));
    EXPECT_TRUE(in->read_image(s, 0, 0, spec.nchannels, OIIO::TypeUnknown, out.bytes.back().data()));
  }
  return out;
}

// Multi-part tiled bands (tiles of 16 over bands of 16 rows, and bands of 9 or 10 rows that end
// inside a tile) stitch to exactly the bytes of the multi-part tiled full render, part by part.
TEST(stitch_cli, multipart_tiled_bands_stitch_to_the_full_render) {
  const std::string dir = scratch_folder("stitch_multipart");
  for (int bands : {3, 5}) {
    const std::vector<std::string> layout = {"--multipart", "--exr-tile-size", "16"};
    const std::string full = render(dir, "full.exr", layout);
    std::vector<std::string> args = {"stitch", dir + "/stitched.exr"};
    for (int i = 0; i < bands; ++i) {
      std::vector<std::string> extra = layout;
      extra.insert(extra.end(), {"--band", std::to_string(i) + "/" + std::to_string(bands)});
      args.push_back(render(dir, "band" + std::to_string(i) + ".exr", extra));
    }
    auto result = run_kiln(args);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    const stored_parts a = read_parts(full), b = read_parts(dir + "/stitched.exr");
    EXPECT_EQ(b.names, (std::vector<std::string>{"rgba", "depth", "N", "id"}));
    EXPECT_EQ(b.names, a.names);
    EXPECT_EQ(b.tile_widths, (std::vector<int>{16, 16, 16, 16}));
    EXPECT_EQ(b.channels, a.channels);
    ASSERT_EQ(b.bytes.size(), a.bytes.size());
    for (size_t k = 0; k < a.bytes.size(); ++k)
      EXPECT_TRUE(a.bytes[k] == b.bytes[k]) << a.names[k] << ", " << bands << " bands";
  }
}

TEST(stitch_cli, overlapping_or_incomplete_inputs_exit_2_naming_the_file) {
  const std::string dir = scratch_folder("stitch_refused");
  const std::string b0 = render(dir, "b0.exr", {"--band", "0/3"});
  const std::string b1 = render(dir, "b1.exr", {"--band", "1/3"});
  const std::string b2 = render(dir, "b2.exr", {"--band", "2/3"});
  const std::string wide = render(dir, "wide.exr", {"--crop", "0,10,64,20"});        // overlaps band 0 and 1
  const std::string other = render(dir, "other.exr", {"--band", "1/3", "--float"});  // float colour
  struct refusal {
    std::vector<std::string> inputs;
    std::string file, problem;
  };
  const std::vector<refusal> cases = {
      {{b0, b1}, b1, "pixel (0, 32) is missing"},
      {{b0, b2}, b2, "pixel (0, 16) is missing"},
      {{b0, b1, b1, b2}, b1, "overlaps"},
      {{b0, wide, b2}, wide, "overlaps [0,64)x[0,16)"},
      {{b0, other, b2}, other, "channel names or formats differ"},
  };
  for (const refusal& c : cases) {
    std::vector<std::string> args = {"stitch", dir + "/out.exr"};
    args.insert(args.end(), c.inputs.begin(), c.inputs.end());
    auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << c.problem;
    ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(c.file + ":"), std::string::npos) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(c.problem), std::string::npos) << result.stderr_text;
  }
  EXPECT_FALSE(std::ifstream(dir + "/out.exr").good());  // nothing written
}

// Bands of two different renders (here: other depth limits) cover the frame but are refused.
TEST(stitch_cli, bands_rendered_with_other_settings_exit_2_naming_the_file) {
  const std::string dir = scratch_folder("stitch_mixed");
  const std::string top = render(dir, "top.exr", {"--band", "0/2"});
  const std::string bottom = render(dir, "bottom.exr", {"--band", "1/2", "--max-depth", "3"});
  auto result = run_kiln({"stitch", dir + "/out.exr", top, bottom});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find(bottom), std::string::npos) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("kiln/frame_settings_hash"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));
}

TEST(stitch_cli, bad_band_requests_exit_2_with_one_line) {
  const std::string dir = scratch_folder("stitch_bad_band");
  for (std::vector<std::string> extra :
       std::vector<std::vector<std::string>>{{"--band", "3/3"},
                                             {"--band", "0/0"},
                                             {"--band", "-1/3"},
                                             {"--band", "1/3x"},
                                             {"--band", "1,3"},
                                             {"--band", "0/49"},
                                             {"--band", "0/2", "--crop", "0,0,4,4"}}) {
    auto result = run_kiln(render_arguments(dir + "/x.exr", extra));
    EXPECT_EQ(result.exit_code, 2) << extra[1];
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find("--band"), std::string::npos) << result.stderr_text;
  }
}

// --tile, the band's name before render tiles and EXR tiles were told apart, renders the same band
// with one warning naming its new name.
TEST(stitch_cli, the_deprecated_tile_option_renders_the_same_band_with_a_warning) {
  const std::string dir = scratch_folder("stitch_tile_alias");
  const command_result old_name = run_kiln(render_arguments(dir + "/tile.exr", {"--tile", "1/3"}));
  ASSERT_EQ(old_name.exit_code, 0) << old_name.stderr_text;
  EXPECT_EQ(lines(old_name.stderr_text).size(), 1u) << old_name.stderr_text;
  EXPECT_NE(old_name.stderr_text.find("--tile is deprecated; use --band"), std::string::npos);
  const image band = read(render(dir, "band.exr", {"--band", "1/3"}));
  const image tile = read(dir + "/tile.exr");
  EXPECT_EQ(tile.spec.y, band.spec.y);
  EXPECT_EQ(tile.spec.height, band.spec.height);
  EXPECT_EQ(tile.pixels, band.pixels);
}

// A region of half RGBA pixels (8 bytes each) at [x, x + width) x [y, y + height) of a display
// window of frame_width x frame_height, written by OpenImageIO.
std::string write_region(const std::string& path, int x, int y, int width, int height, int frame_width,
                         int frame_height) {
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::HALF);
  spec.x = x;
  spec.y = y;
  spec.full_width = frame_width;
  spec.full_height = frame_height;
  const std::vector<float> pixels(size_t(width) * size_t(height) * 4, 0.5f);
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out && out->open(path, spec)) << path;
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  out->close();
  return path;
}

// The regions and the frame are charged to a memory budget before they are made: past it, one line
// names what needed the memory, its size and the budget. Stitch said only "out of memory" (a region
// claiming 100000² pixels) or allocated a map of the whole frame to find a gap in it.
TEST(stitch_cli, a_frame_or_region_past_the_memory_budget_is_refused_naming_its_size) {
  const std::string dir = scratch_folder("stitch_memory");
  const std::string top = write_region(dir + "/top.exr", 0, 0, 64, 32, 64, 64);
  const std::string bottom = write_region(dir + "/bottom.exr", 0, 32, 64, 32, 64, 64);
  const std::string out = dir + "/out.exr";
  // The regions take 32 KiB; the frame 32 KiB more.
  command_result result = run_kiln({"stitch", out, top, bottom, "--max-memory", "48K"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.stderr_text,
            "kiln: " + top +
                ": the stitched frame's pixels (display window [0,64)x[0,64), 8 bytes each) "
                "need about 32 KiB more, 64 KiB in all, over the memory budget of 48 KiB "
                "(raise it with --max-memory)\n");
  EXPECT_FALSE(std::ifstream(out).good());
  result = run_kiln({"stitch", out, top, bottom, "--max-memory", "64K"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;

  const std::string huge = dir + "/huge.exr";
  // With an empty line offset table (one 8-byte entry a row) the file opens; its pixels are absent.
  std::ofstream(huge, std::ios::binary)
      << testing::exr_header_claiming(100000, 100000) << std::string(size_t(100000) * 8, '\0');
  result = run_kiln({"stitch", dir + "/huge_out.exr", huge, "--max-memory", "1G"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.stderr_text, "kiln: " + huge +
                                    ": the data window's pixels need about 56 GiB, over the memory budget of "
                                    "1.0 GiB (raise it with --max-memory)\n");

  // Two 4x4 regions of a 100000² frame leave a gap, found without a map of the frame.
  const std::string left = write_region(dir + "/left.exr", 0, 0, 4, 4, 100000, 100000);
  const std::string right = write_region(dir + "/right.exr", 4, 0, 4, 4, 100000, 100000);
  result = run_kiln({"stitch", dir + "/gap.exr", left, right, "--max-memory", "1M"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(
      result.stderr_text.find(right + ": dataWindow: with this file the 2 inputs still do not cover the "
                                      "display window [0,100000)x[0,100000): pixel (8, 0) is missing"),
      std::string::npos)
      << result.stderr_text;
}

}  // namespace
}  // namespace kiln
