// `kiln render`'s storage and preview options end to end: --channel-format per layer, --compression
// per part (lossy codecs refused where they would reach Z, P or ids of a single part), --tiled,
// --multipart part names with the single-part pixels, and --preview's PNG and JPEG against the
// documented view transform applied to the EXR as written.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::command_result;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

command_result render_to(const std::string& path, const std::vector<std::string>& extra,
                         const std::string& scene = demo_scene) {
  std::vector<std::string> args = {"render", scene, "-o", path, "--width", "32", "--height", "24", "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_kiln(args);
}

// Renders into dir/name; a failed render fails the test.
std::string render(const std::string& dir, const std::string& name, const std::vector<std::string>& extra,
                   const std::string& scene = demo_scene) {
  const command_result result = render_to(dir + "/" + name, extra, scene);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return dir + "/" + name;
}

struct part {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // every channel as float: exact for half and float
};

std::vector<part> read_parts(const std::string& path) {
  std::vector<part> parts;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return parts;
  for (int s = 0; in->seek_subimage(s, 0); ++s) {
    part p{in->spec(), {}};
    p.pixels.resize(p.spec.image_pixels() * size_t(p.spec.nchannels));
    EXPECT_TRUE(in->read_image(s, 0, 0, p.spec.nchannels, OIIO::TypeDesc::FLOAT, p.pixels.data()));
    parts.push_back(std::move(p));
  }
  return parts;
}

// Channel name -> stored format, over every part.
std::map<std::string, OIIO::TypeDesc> formats(const std::string& path) {
  std::map<std::string, OIIO::TypeDesc> out;
  for (const part& p : read_parts(path))
    for (int c = 0; c < p.spec.nchannels; ++c) out[p.spec.channelnames[size_t(c)]] = p.spec.channelformat(c);
  return out;
}

// Channel name -> its values in raster order, over every part.
std::map<std::string, std::vector<float>> values(const std::string& path) {
  std::map<std::string, std::vector<float>> out;
  for (const part& p : read_parts(path)) {
    const size_t n = size_t(p.spec.nchannels);
    for (size_t c = 0; c < n; ++c)
      for (size_t i = 0; i < p.spec.image_pixels(); ++i)
        out[p.spec.channelnames[c]].push_back(p.pixels[i * n + c]);
  }
  return out;
}

void expect_usage_error(const command_result& result, const std::vector<std::string>& words) {
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  for (const std::string& w : words)
    EXPECT_NE(result.stderr_text.find(w), std::string::npos) << result.stderr_text;
}

TEST(exr_storage_cli, channel_format_sets_each_colour_like_layer) {
  const std::string dir = scratch_folder("storage_formats");
  const std::string aovs = "beauty,Z,N,P,albedo,uv,id";
  const auto mixed =
      formats(render(dir, "mixed.exr", {"--aovs", aovs, "--channel-format", "beauty=float,uv=float"}));
  const auto mostly_float =
      formats(render(dir, "float.exr", {"--aovs", aovs, "--float", "--channel-format", "N=half,Z=float"}));
  ASSERT_EQ(mixed.size(), 19u);
  for (const auto& [name, format] : mixed) {
    const bool half = name.rfind("N.", 0) == 0 || name.rfind("albedo.", 0) == 0;
    EXPECT_EQ(format, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT) << name;
    EXPECT_EQ(mostly_float.at(name), name.rfind("N.", 0) == 0 ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT)
        << name;
  }
}

TEST(exr_storage_cli, data_layers_cannot_be_half_and_bad_entries_are_usage_errors) {
  const std::string dir = scratch_folder("storage_refused");
  for (const std::string aov : {"Z", "P", "id"})
    expect_usage_error(render_to(dir + "/x.exr", {"--channel-format", aov + "=half"}),
                       {"--channel-format", aov + " is always 32-bit float"});
  expect_usage_error(render_to(dir + "/x.exr", {"--channel-format", "beauty=double"}), {"AOV=half"});
  expect_usage_error(render_to(dir + "/x.exr", {"--channel-format", "rgba=half"}), {"unknown AOV 'rgba'"});
  expect_usage_error(render_to(dir + "/x.exr", {"--compression", "lzw"}), {"--compression"});
  expect_usage_error(render_to(dir + "/x.exr", {"--compression", "piz", "--compression-level", "3"}),
                     {"--compression-level", "piz takes no level"});
  expect_usage_error(render_to(dir + "/x.exr", {"--compression-level", "12"}), {"1 to 9"});
  expect_usage_error(render_to(dir + "/x.exr", {"--preview", dir + "/x.tif"}), {"--preview", ".png"});
  expect_usage_error(render_to(dir + "/x.exr", {"--aovs", "Z", "--preview", dir + "/x.png"}), {"beauty"});
  EXPECT_FALSE(std::ifstream(dir + "/x.exr").good());
}

TEST(exr_storage_cli, lossy_codecs_are_refused_for_single_part_data_and_kept_off_data_parts) {
  const std::string dir = scratch_folder("storage_lossy");
  for (const std::string codec : {"pxr24", "b44", "b44a", "dwaa", "dwab"}) {
    expect_usage_error(render_to(dir + "/lossy.exr", {"--compression", codec}),
                       {"--compression: " + codec + " is lossy", "would alter Z", "--multipart"});
    EXPECT_FALSE(std::ifstream(dir + "/lossy.exr").good()) << codec;
    const std::string file =
        render(dir, codec + ".exr", {"--compression", codec, "--multipart", "--aovs", "beauty,Z,N,P,id"});
    std::vector<std::string> codecs;
    for (const part& p : read_parts(file)) codecs.push_back(p.spec.get_string_attribute("compression"));
    EXPECT_EQ(codecs, (std::vector<std::string>{codec, "zip", codec, "zip", "zip"}));  // rgba depth N P id
  }
  // No data layer in the file: one part may be lossy.
  const std::string beauty = render(dir, "beauty.exr", {"--compression", "dwaa", "--aovs", "beauty,N"});
  EXPECT_EQ(read_parts(beauty).front().spec.get_string_attribute("compression"), "dwaa");
  for (const std::string codec : {"none", "rle", "zips", "zip", "piz"})
    EXPECT_EQ(read_parts(render(dir, codec + ".exr", {"--compression", codec}))
                  .front()
                  .spec.get_string_attribute("compression"),
              codec);
  EXPECT_EQ(read_parts(render(dir, "default.exr", {})).front().spec.get_string_attribute("compression"),
            "zip");
}

// OpenEXR records no zip level, so the level shows in the size: zlib level 1 packs these pixels
// looser than level 9 (83,118 against 74,561 bytes; the headers differ by one character), and both
// decode to the same values.
TEST(exr_storage_cli, zip_level_changes_the_size_never_the_pixels) {
  const std::string dir = scratch_folder("storage_zip_level");
  const std::string a = dir + "/fast.exr", b = dir + "/small.exr";
  for (const auto& [path, level] : {std::pair{a, "1"}, std::pair{b, "9"}}) {
    const command_result result =
        run_kiln({"render", demo_scene, "-o", path, "-q", "--width", "96", "--height", "72", "--aovs",
                  "beauty,Z,N,P,albedo,uv,id", "--compression-level", level});
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  }
  EXPECT_GT(std::filesystem::file_size(a), std::filesystem::file_size(b) + 1000);
  const auto va = values(a), vb = values(b);
  ASSERT_EQ(va.size(), 19u);
  for (const auto& [name, pixels] : va)
    EXPECT_EQ(std::memcmp(pixels.data(), vb.at(name).data(), pixels.size() * sizeof(float)), 0) << name;
}

TEST(exr_storage_cli, tiled_and_multipart_files_hold_the_single_part_scanline_pixels) {
  const std::string dir = scratch_folder("storage_layout");
  const std::vector<std::string> aovs = {"--aovs", "beauty,Z,N,P,albedo,uv,id"};
  auto with = [&aovs](std::vector<std::string> extra) {
    extra.insert(extra.end(), aovs.begin(), aovs.end());
    return extra;
  };
  const std::string plain = render(dir, "plain.exr", with({}));
  const std::string tiled = render(dir, "tiled.exr", with({"--tiled"}));
  const std::string tiled16 = render(dir, "tiled16.exr", with({"--exr-tile-size", "16"}));
  const std::string multi =
      render(dir, "multi.exr", with({"--multipart", "--tiled", "--exr-tile-size", "8"}));
  EXPECT_EQ(read_parts(plain).front().spec.tile_width, 0);  // scanlines
  EXPECT_EQ(read_parts(tiled).front().spec.tile_width, 64);
  EXPECT_EQ(read_parts(tiled).front().spec.tile_height, 64);
  EXPECT_EQ(read_parts(tiled16).front().spec.tile_width, 16);
  const std::vector<part> parts = read_parts(multi);
  std::vector<std::string> names;
  for (const part& p : parts) {
    names.push_back(p.spec.get_string_attribute("oiio:subimagename"));
    EXPECT_EQ(p.spec.tile_width, 8) << names.back();
    EXPECT_EQ(p.spec.get_string_attribute("kiln/aovs"), "beauty,Z,N,P,albedo,uv,id") << names.back();
  }
  EXPECT_EQ(names, (std::vector<std::string>{"rgba", "depth", "N", "P", "albedo", "uv", "id"}));
  const auto reference = values(plain);
  ASSERT_EQ(reference.size(), 19u);
  for (const std::string& other : {tiled, tiled16, multi}) {
    const auto v = values(other);
    ASSERT_EQ(v.size(), reference.size()) << other;
    for (const auto& [name, pixels] : reference) {
      ASSERT_EQ(v.at(name).size(), pixels.size());
      EXPECT_EQ(std::memcmp(v.at(name).data(), pixels.data(), pixels.size() * sizeof(float)), 0)
          << other << " " << name;
    }
  }
}

// The documented view transform, written out independently of kiln's code.
int srgb_code(double linear, double exposure) {
  double v = std::clamp(linear * std::pow(2.0, exposure), 0.0, 1.0);
  v = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return int(std::lround(255.0 * v));
}

struct preview_image {
  OIIO::ImageSpec spec;
  std::vector<unsigned char> codes;
};

// The codes as stored: OpenImageIO would otherwise multiply a PNG's colour by its alpha on reading.
preview_image read_preview(const std::string& path) {
  preview_image out;
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return out;
  out.spec = in->spec();
  out.codes.resize(out.spec.image_pixels() * size_t(out.spec.nchannels));
  EXPECT_TRUE(in->read_image(0, 0, 0, out.spec.nchannels, OIIO::TypeDesc::UINT8, out.codes.data()));
  return out;
}

TEST(exr_storage_cli, png_preview_is_the_view_transform_of_the_exr_within_one_code) {
  const std::string dir = scratch_folder("storage_preview_png");
  for (double exposure : {0.0, 1.5, -2.0}) {
    const std::string png = dir + "/preview.png";
    // 4 samples a pixel: pixels on the quadric showcase's horizon have alpha strictly between 0
    // and 1 (the demo room is closed: every pixel of it is covered).
    const std::string exr = render(
        dir, "preview.exr",
        {"--preview", png, "--preview-exposure", std::to_string(exposure), "--multipart", "--spp", "4"},
        std::string(KILN_SOURCE_DIR) + "/scenes/quadric_showcase.gltf");
    const auto v = values(exr);
    const preview_image p = read_preview(png);
    ASSERT_EQ(p.spec.nchannels, 4);
    ASSERT_EQ(p.spec.image_pixels(), v.at("R").size());
    int worst = 0;
    size_t partial = 0;
    const char* names[4] = {"R", "G", "B", "A"};
    for (size_t i = 0; i < p.spec.image_pixels(); ++i)
      for (int c = 0; c < 4; ++c) {
        partial += c == 3 && p.codes[i * 4 + 3] > 0 && p.codes[i * 4 + 3] < 255;
        const double x = v.at(names[c])[i], a = std::clamp(double(v.at("A")[i]), 0.0, 1.0);
        // PNG holds straight colour: the premultiplied colour divided by alpha where there is any.
        const int expected = c < 3 ? srgb_code(a > 0.0 ? x / a : x, exposure)
                                   : int(std::lround(255.0 * std::clamp(x, 0.0, 1.0)));
        worst = std::max(worst, std::abs(int(p.codes[i * 4 + size_t(c)]) - expected));
      }
    EXPECT_LE(worst, 1) << "exposure " << exposure;
    EXPECT_GT(partial, 10u);  // pixels where unpremultiplying matters
  }
}

// An unlit square of base colour (0.2, 0.5, 0.8) over the left half of the frame, background
// (alpha 0) on the right. Seen from (0, 0, 5) its edge x = 0 lies on the pixel boundary at x = 16,
// so every 8x8 luma and 16x16 chroma block of a JPEG is flat and JPEG reproduces it closely.
std::string flat_square_scene(const std::string& dir) {
  testing::gltf_builder b;
  int flat = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.5, 0.8, 1.0}}}},
                             {"doubleSided", true},
                             {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}});
  b.doc["extensionsUsed"].push_back("KHR_materials_unlit");
  b.add_node({{"mesh", b.add_mesh({{-20, -20, 0}, {0, -20, 0}, {0, 20, 0}, {-20, 20, 0}}, {0, 1, 2, 0, 2, 3},
                                  flat)}});
  const std::string path = dir + "/square.gltf";
  b.write(path);
  return path;
}

TEST(exr_storage_cli, preview_of_a_flat_square_keeps_alpha_in_png_and_colour_in_jpeg) {
  const std::string dir = scratch_folder("storage_preview_flat");
  const std::string scene = flat_square_scene(dir);
  const std::vector<std::string> view = {"--look-from", "0,0,5", "--look-at", "0,0,0"};
  auto with = [&view](std::vector<std::string> extra) {
    extra.insert(extra.end(), view.begin(), view.end());
    return extra;
  };
  render(dir, "png.exr", with({"--preview", dir + "/square.png"}), scene);
  render(dir, "jpg.exr", with({"--preview", dir + "/square.jpg", "--preview-exposure", "1"}), scene);
  const preview_image png = read_preview(dir + "/square.png"), jpg = read_preview(dir + "/square.jpg");
  ASSERT_EQ(png.spec.nchannels, 4);
  ASSERT_EQ(jpg.spec.nchannels, 3);  // JPEG has no alpha: the colour over black
  ASSERT_EQ(png.spec.width, 32);
  ASSERT_EQ(jpg.spec.width, 32);
  // Half rounds 0.2, 0.5, 0.8 by under 2^-11 relative: not enough to move a code at these values.
  const int square[3] = {srgb_code(0.2, 0), srgb_code(0.5, 0), srgb_code(0.8, 0)};
  const int bright[3] = {srgb_code(0.2, 1), srgb_code(0.5, 1), srgb_code(0.8, 1)};
  EXPECT_EQ(square[0], 124);  // sRGB of 0.2 is 0.4845
  auto at = [](const preview_image& p, int x, int y, int c) {
    return int(
        p.codes[(size_t(y) * size_t(p.spec.width) + size_t(x)) * size_t(p.spec.nchannels) + size_t(c)]);
  };
  int jpeg_worst = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      const bool inside = x < 16;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(at(png, x, y, c), inside ? square[c] : 0) << x << "," << y;
        // The decoder's chroma upsampling blends across the edge: columns 15 and 16 are left out.
        if (x != 15 && x != 16)
          jpeg_worst = std::max(jpeg_worst, std::abs(at(jpg, x, y, c) - (inside ? bright[c] : 0)));
      }
      EXPECT_EQ(at(png, x, y, 3), inside ? 255 : 0) << x << "," << y;
    }
  // JPEG: stated tolerance of 3 codes (YCbCr rounding and quantisation at quality 95) off the edge.
  EXPECT_LE(jpeg_worst, 3);
}

}  // namespace
}  // namespace kiln
