#include "io/exr/exr_writer.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "io/exr/exr_reader.h"
#include "io/exr/preview_writer.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir() {
  fs::path dir = fs::temp_directory_path() / ("kiln_exr_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// Settings with every colour-like layer in one format.
exr_settings all_layers(sample_format format) {
  exr_settings s;
  for (sample_format& f : s.formats.of) f = format;
  return s;
}

const exr_settings full_float = all_layers(sample_format::float32);

film test_film() {
  film f(5, 3);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      size_t i = f.index(x, y);
      f.color[i] = vec4(0.25f * x, 0.5f * y, 1.0f / 3.0f, 1.0f);
      f.depth[i] = x == 0 ? inf : 1.0f + x + 10.0f * y;
      f.vec3_layer(aov::normal)[i] = vec3(0.0f, 1.0f, 0.0f);
    }
  return f;
}

TEST(exr_writer, round_trips_channels_and_metadata) {
  fs::path file = scratch_dir() / "out.exr";
  exr_metadata metadata;
  metadata.world_to_camera[3][0] = 7.0;  // a translation, stored in the last row by OpenEXR
  // w = camera z (column-vector row 3, column 2): OpenEXR's row vectors read it at M[2][3].
  metadata.world_to_ndc = dmat4(0.0);
  metadata.world_to_ndc[2][3] = 1.0;
  metadata.attributes = {{"kiln/spp", "4"}};
  write_exr(file.string(), test_film(), full_float, metadata);

  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  ASSERT_EQ(spec.nchannels, 8);
  EXPECT_EQ(spec.channelnames[4], "Z");
  EXPECT_EQ(spec.channelnames[5], "N.X");
  EXPECT_EQ(spec.get_string_attribute("kiln/spp"), "4");
  const OIIO::ParamValue* w2c = spec.find_attribute("worldToCamera");
  ASSERT_NE(w2c, nullptr);
  EXPECT_FLOAT_EQ(static_cast<const float*>(w2c->data())[12], 7.0f);
  const OIIO::ParamValue* w2n = spec.find_attribute("worldToNDC");
  ASSERT_NE(w2n, nullptr);
  EXPECT_FLOAT_EQ(static_cast<const float*>(w2n->data())[2 * 4 + 3], 1.0f);
  EXPECT_FLOAT_EQ(static_cast<const float*>(w2n->data())[3 * 4 + 2], 0.0f);

  std::vector<float> pixels(5 * 3 * 8);
  ASSERT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, pixels.data()));
  // Pixel (2, 1): R = 0.5, G = 0.5, Z = 1 + 2 + 10.
  const float* p = &pixels[(1 * 5 + 2) * 8];
  EXPECT_FLOAT_EQ(p[0], 0.5f);
  EXPECT_FLOAT_EQ(p[1], 0.5f);
  EXPECT_FLOAT_EQ(p[2], 1.0f / 3.0f);
  EXPECT_FLOAT_EQ(p[4], 13.0f);
  EXPECT_TRUE(std::isinf(pixels[4]));  // background depth stays +inf
}

TEST(exr_writer, half_colour_keeps_float_depth) {
  fs::path file = scratch_dir() / "half.exr";
  write_exr(file.string(), test_film(), exr_settings{}, exr_metadata{});
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_EQ(in->spec().channelformat(4), OIIO::TypeDesc::FLOAT);
}

// A colour beyond half's range would be written as +inf; it saturates at 65504 instead, and
// float output keeps it exactly.
TEST(exr_writer, half_colour_saturates_instead_of_becoming_infinite) {
  film f = test_film();
  f.color[f.index(1, 1)] = vec4(1e6f, -3e5f, 70000.0f, 1.0f);
  for (bool as_float : {false, true}) {
    fs::path file = scratch_dir() / (as_float ? "bright_float.exr" : "bright_half.exr");
    write_exr(file.string(), f, as_float ? full_float : exr_settings{}, exr_metadata{});
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    std::vector<float> pixels(5 * 3 * 8);
    ASSERT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, pixels.data()));
    const float* p = &pixels[(1 * 5 + 1) * 8];
    EXPECT_EQ(p[0], as_float ? 1e6f : 65504.0f);
    EXPECT_EQ(p[1], as_float ? -3e5f : -65504.0f);
    EXPECT_EQ(p[2], as_float ? 70000.0f : 65504.0f);
    EXPECT_EQ(p[3], 1.0f);
  }
}

// A film with every AOV, values that half cannot hold exactly (so a format mix-up shows), 7x5 so
// 4x4 tiles leave partial tiles at the right and bottom edges.
film all_aov_film() {
  const aov_set all =
      aov_set_of({aov::beauty, aov::depth, aov::normal, aov::position, aov::albedo, aov::uv, aov::ids});
  film f(7, 5, all);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t i = f.index(x, y);
      const float t = 0.1f + 0.013f * float(i);
      f.color[i] = vec4(t, 2.0f * t, 1.0f / 3.0f, 1.0f);
      f.depth[i] = x == 0 ? inf : 100.0f + 0.001f * float(i);
      f.vec3_layer(aov::normal)[i] = vec3(t, 0.7f, -t);
      f.vec3_layer(aov::position)[i] = vec3(1000.0f + 0.001f * float(i), -t, 3.0f);
      f.vec3_layer(aov::albedo)[i] = vec3(t, 0.5f, 0.25f);
      f.uv[i] = vec2(t, 1.0f - t);
      f.ids[i] = glm::ivec3(int(i), 70000 + int(i), x == 0 ? -1 : 3);
    }
  return f;
}

// Every part of an EXR: its spec and its pixels as float (exact for half and float).
struct part_contents {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;
};

std::vector<part_contents> read_parts(const fs::path& file) {
  std::vector<part_contents> parts;
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return parts;
  for (int s = 0; in->seek_subimage(s, 0); ++s) {
    part_contents p{in->spec(), {}};
    p.pixels.resize(p.spec.image_pixels() * size_t(p.spec.nchannels));
    EXPECT_TRUE(in->read_image(s, 0, 0, p.spec.nchannels, OIIO::TypeDesc::FLOAT, p.pixels.data()));
    parts.push_back(std::move(p));
  }
  return parts;
}

// Channel name -> (format, values) over every part of a file.
std::map<std::string, std::pair<OIIO::TypeDesc, std::vector<float>>> channels_of(const fs::path& file) {
  std::map<std::string, std::pair<OIIO::TypeDesc, std::vector<float>>> out;
  for (const part_contents& p : read_parts(file)) {
    const size_t n = size_t(p.spec.nchannels);
    for (size_t c = 0; c < n; ++c) {
      auto& [format, values] = out[p.spec.channelnames[c]];
      format = p.spec.channelformat(int(c));
      for (size_t i = 0; i < p.spec.image_pixels(); ++i) values.push_back(p.pixels[i * n + c]);
    }
  }
  return out;
}

TEST(exr_writer, each_colour_like_layer_takes_its_own_format_and_data_layers_stay_float) {
  fs::path file = scratch_dir() / "formats.exr";
  exr_settings s;
  s.formats[aov::beauty] = sample_format::float32;
  s.formats[aov::albedo] = sample_format::float32;
  s.formats[aov::uv] = sample_format::half;  // N (by default) and uv (asked for) half
  write_exr(file.string(), all_aov_film(), s, exr_metadata{});
  const auto channels = channels_of(file);
  ASSERT_EQ(channels.size(), 19u);
  for (const auto& [name, contents] : channels) {
    const bool half = name.rfind("N.", 0) == 0 || name.rfind("uv.", 0) == 0;
    EXPECT_EQ(contents.first, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT) << name;
  }
  // Float keeps 0.1 + 0.013 exactly; half rounds it to 11 bits.
  EXPECT_EQ(channels.at("R").second[0], 0.1f);
  EXPECT_EQ(channels.at("albedo.R").second[0], 0.1f);
  EXPECT_NE(channels.at("N.X").second[0], 0.1f);
  EXPECT_NEAR(channels.at("N.X").second[0], 0.1f, 1e-4f);
  EXPECT_EQ(channels.at("id.material").second[34], 70034.0f);  // beyond half's exact integers
  EXPECT_EQ(channels.at("P.X").second[34], 1000.0f + 0.001f * 34.0f);
}

TEST(exr_writer, multipart_writes_one_named_part_per_layer_with_the_single_part_pixels) {
  const fs::path single = scratch_dir() / "single.exr", multi = scratch_dir() / "multi.exr";
  exr_metadata metadata;
  metadata.attributes = {{"kiln/spp", "4"}};
  exr_settings s;
  write_exr(single.string(), all_aov_film(), s, metadata);
  s.multipart = true;
  write_exr(multi.string(), all_aov_film(), s, metadata);

  const std::vector<part_contents> parts = read_parts(multi);
  std::vector<std::string> names;
  for (const part_contents& p : parts) {
    names.push_back(p.spec.get_string_attribute("oiio:subimagename"));
    EXPECT_EQ(p.spec.get_string_attribute("kiln/spp"), "4") << names.back();  // every part: the header
    EXPECT_NE(p.spec.find_attribute("worldToCamera"), nullptr) << names.back();
  }
  EXPECT_EQ(names, (std::vector<std::string>{"rgba", "depth", "N", "P", "albedo", "uv", "id"}));
  EXPECT_EQ(parts[0].spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(parts[1].spec.channelnames, (std::vector<std::string>{"Z"}));
  // OpenEXR stores a part's channels sorted by name.
  EXPECT_EQ(parts[6].spec.channelnames,
            (std::vector<std::string>{"id.instance", "id.material", "id.object"}));
  EXPECT_EQ(read_parts(single).size(), 1u);

  const auto a = channels_of(single), b = channels_of(multi);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, contents] : a) {
    ASSERT_EQ(b.count(name), 1u) << name;
    EXPECT_EQ(b.at(name).first, contents.first) << name;
    const auto& va = contents.second;
    const auto& vb = b.at(name).second;
    ASSERT_EQ(va.size(), vb.size());
    EXPECT_EQ(std::memcmp(va.data(), vb.data(), va.size() * sizeof(float)), 0) << name;  // +inf Z included
  }
}

TEST(exr_writer, lossy_codecs_reach_only_colour_like_parts) {
  for (const std::string codec : {"pxr24", "b44", "b44a", "dwaa", "dwab"}) {
    fs::path file = scratch_dir() / ("lossy_" + codec + ".exr");
    exr_settings s;
    s.compression = codec;
    try {
      write_exr(file.string(), all_aov_film(), s, exr_metadata{});
      ADD_FAILURE() << codec << ": a single part with Z, P and ids was written lossily";
    } catch (const error& e) {
      EXPECT_EQ(e.kind(), error_kind::input);
      EXPECT_NE(std::string(e.what()).find("--multipart"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(file));
    s.multipart = true;
    write_exr(file.string(), all_aov_film(), s, exr_metadata{});
    for (const part_contents& p : read_parts(file)) {
      const std::string part = p.spec.get_string_attribute("oiio:subimagename");
      const bool data = part == "depth" || part == "P" || part == "id";
      EXPECT_EQ(p.spec.get_string_attribute("compression"), data ? "zip" : codec) << part;
    }
  }
  // Without data layers a single part may use a lossy codec.
  film beauty_only = all_aov_film();
  beauty_only.aovs = aov_set_of({aov::beauty});
  exr_settings s;
  s.compression = "dwab";
  EXPECT_NO_THROW(check_exr_settings(beauty_only.aovs, s));
  EXPECT_THROW(check_exr_settings(aov_set{}, s), error);  // the default holds Z
}

TEST(exr_writer, lossless_codecs_round_trip_every_bit_and_levels_are_recorded) {
  const auto reference = channels_of([] {
    fs::path file = scratch_dir() / "reference.exr";
    write_exr(file.string(), all_aov_film(), exr_settings{}, exr_metadata{});
    return file;
  }());
  for (const std::string codec : {"none", "rle", "zips", "zip", "piz"}) {
    fs::path file = scratch_dir() / ("lossless_" + codec + ".exr");
    exr_settings s;
    s.compression = codec;
    write_exr(file.string(), all_aov_film(), s, exr_metadata{});
    EXPECT_EQ(read_parts(file).front().spec.get_string_attribute("compression"), codec);
    const auto channels = channels_of(file);
    for (const auto& [name, contents] : reference)
      EXPECT_EQ(std::memcmp(contents.second.data(), channels.at(name).second.data(),
                            contents.second.size() * sizeof(float)),
                0)
          << codec << " " << name;
  }
  fs::path file = scratch_dir() / "dwa_level.exr";
  exr_settings s;
  s.compression = "dwaa";
  s.compression_level = 200;
  s.multipart = true;
  write_exr(file.string(), all_aov_film(), s, exr_metadata{});
  EXPECT_EQ(read_parts(file).front().spec.get_float_attribute("openexr:dwaCompressionLevel"), 200.0f);
}

// A beauty-only film of smooth colour with a fixed-seed ripple of noise: what zlib and DCT codecs
// compress better the coarser they may be, 96x64 so DWA sees whole 32-line blocks.
film textured_film() {
  film f(96, 64, aov_set_of({aov::beauty}));
  uint32_t state = 12345;
  for (size_t i = 0; i < f.color.size(); ++i) {
    state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG
    const float noise = float(state >> 8) / float(1 << 24);
    const float x = float(i % 96) / 96.0f, y = float(i / 96) / 64.0f;
    f.color[i] = vec4(x + 0.05f * noise, y, 0.5f * (x + y) + 0.02f * noise, 1.0f);
  }
  return f;
}

// The zlib level lives in the writer only (no attribute records it), so only the bytes tell
// whether it reached the compressor: level 9 stores the same pixels in fewer bytes than level 1.
TEST(exr_writer, zip_level_reaches_the_compressor_and_keeps_every_bit) {
  const fs::path fast = scratch_dir() / "zip1.exr", small = scratch_dir() / "zip9.exr";
  for (const auto& [file, level] : {std::pair{fast, 1}, std::pair{small, 9}}) {
    exr_settings s;
    s.compression = "zip";
    s.compression_level = level;
    write_exr(file.string(), textured_film(), s, exr_metadata{});
    EXPECT_EQ(read_parts(file).front().spec.get_string_attribute("compression"), "zip");
  }
  EXPECT_LT(fs::file_size(small), fs::file_size(fast));
  const auto a = channels_of(fast), b = channels_of(small);
  ASSERT_EQ(a.size(), 4u);
  for (const auto& [name, contents] : a)
    EXPECT_EQ(
        std::memcmp(contents.second.data(), b.at(name).second.data(), contents.second.size() * sizeof(float)),
        0)
        << name;
}

// dwaCompressionLevel is both an attribute readers show and the quantisation the compressor uses;
// a file read back and written again (kiln stitch) must keep using the level it records.
TEST(exr_writer, dwa_level_is_recorded_and_drives_the_compressor_also_when_written_back) {
  const fs::path fine = scratch_dir() / "dwa45.exr", coarse = scratch_dir() / "dwa2000.exr";
  for (const auto& [file, level] : {std::pair{fine, 0}, std::pair{coarse, 2000}}) {
    exr_settings s;
    s.compression = "dwab";
    s.compression_level = level;
    write_exr(file.string(), textured_film(), s, exr_metadata{});
    const OIIO::ImageSpec spec = read_parts(file).front().spec;
    EXPECT_EQ(spec.get_string_attribute("compression"), "dwab");
    EXPECT_EQ(spec.get_float_attribute("openexr:dwaCompressionLevel"), level == 0 ? 45.0f : 2000.0f);
  }
  EXPECT_LT(fs::file_size(coarse), fs::file_size(fine));
  // The same pixels written back at the level they record, and again with the level set to 45.
  exr_image image = read_exr(coarse.string());
  EXPECT_EQ(exr_float_attribute(image, "dwaCompressionLevel"), 2000.0f);
  const fs::path kept = scratch_dir() / "dwa2000_copy.exr", finer = scratch_dir() / "dwa2000_at45.exr";
  write_exr(kept.string(), image);
  set_exr_attribute(image, "dwaCompressionLevel", 45.0f);
  write_exr(finer.string(), image);
  EXPECT_EQ(read_parts(kept).front().spec.get_float_attribute("openexr:dwaCompressionLevel"), 2000.0f);
  EXPECT_EQ(read_parts(finer).front().spec.get_float_attribute("openexr:dwaCompressionLevel"), 45.0f);
  EXPECT_LT(fs::file_size(kept), fs::file_size(finer));
}

// What the preview takes from memory is what reading the file back gives, bit for bit: half and
// float beauties, one part or several, lossless codecs, a crop, and values half cannot hold (NaN,
// past 65504, below its smallest normal); under a lossy codec it must read the file instead.
TEST(exr_writer, stored_beauty_is_the_file_s_beauty_bit_for_bit_under_lossless_codecs) {
  film f = all_aov_film();
  f.x0 = 2;
  f.y0 = 3;
  f.full_width = 20;
  f.full_height = 10;
  f.color[0] = vec4(std::nanf(""), 1e6f, 1e-6f, 0.5f);
  f.color[1] = vec4(-3.0f, 70000.0f, 3e-8f, 0.0f);
  for (const sample_format format : {sample_format::half, sample_format::float32})
    for (const std::string codec : {"none", "zip", "piz"})
      for (const bool multipart : {false, true}) {
        exr_settings s = all_layers(format);
        s.compression = codec;
        s.multipart = multipart;
        const fs::path file = scratch_dir() / "stored_beauty.exr";
        write_exr(file.string(), f, s, exr_metadata{});
        const std::optional<rgba_image> stored = stored_beauty(f, s), read = read_exr_beauty(file.string());
        ASSERT_TRUE(stored && read) << codec;
        EXPECT_EQ(stored->width, 7);
        EXPECT_EQ(stored->height, 5);
        EXPECT_EQ(read->width, 7);
        ASSERT_EQ(stored->pixels.size(), read->pixels.size());
        EXPECT_EQ(
            std::memcmp(stored->pixels.data(), read->pixels.data(), read->pixels.size() * sizeof(float)), 0)
            << codec << (multipart ? " multipart" : "")
            << (format == sample_format::half ? " half" : " float");
      }
  exr_settings lossy;
  lossy.compression = "dwab";
  EXPECT_FALSE(stored_beauty(f, lossy));
  EXPECT_FALSE(stored_beauty(film(2, 2, aov_set_of({aov::depth, aov::normal})), exr_settings{}));
}

TEST(exr_writer, tiled_files_record_the_tile_size_and_scanline_files_none) {
  for (int tile : {0, 4, 64}) {
    for (bool multipart : {false, true}) {
      fs::path file = scratch_dir() / ("tiles_" + std::to_string(tile) + (multipart ? "_multi.exr" : ".exr"));
      exr_settings s;
      s.tile_size = tile;
      s.multipart = multipart;
      write_exr(file.string(), all_aov_film(), s, exr_metadata{});
      for (const part_contents& p : read_parts(file)) {
        EXPECT_EQ(p.spec.tile_width, tile);
        EXPECT_EQ(p.spec.tile_height, tile);
      }
      EXPECT_EQ(channels_of(file).at("id.object").second[34], 34.0f);
    }
  }
}

// kiln's own reader (used by kiln stitch) flattens parts and tiles into one channel list; writing
// what it read gives back the same parts, tiles and values.
TEST(exr_reader, reads_multipart_tiled_files_and_writes_them_back_unchanged) {
  const fs::path single = scratch_dir() / "read_single.exr", multi = scratch_dir() / "read_multi.exr",
                 copy = scratch_dir() / "read_copy.exr";
  exr_settings s;
  write_exr(single.string(), all_aov_film(), s, exr_metadata{});
  s.multipart = true;
  s.tile_size = 4;
  write_exr(multi.string(), all_aov_film(), s, exr_metadata{});
  const exr_image a = read_exr(single.string()), b = read_exr(multi.string());
  EXPECT_EQ(b.channel_names.size(), 19u);
  EXPECT_EQ(b.pixels.size(), a.pixels.size());
  // Part after part, each in its channel list's (the file's, alphabetical) order: rgba comes first.
  EXPECT_EQ(std::vector<std::string>(b.channel_names.begin(), b.channel_names.begin() + 5),
            (std::vector<std::string>{"A", "B", "G", "R", "Z"}));
  EXPECT_EQ(std::vector<std::string>(b.channel_formats.begin(), b.channel_formats.begin() + 5),
            (std::vector<std::string>{"half", "half", "half", "half", "float"}));
  write_exr(copy.string(), b);
  const std::vector<part_contents> original = read_parts(multi), copied = read_parts(copy);
  ASSERT_EQ(copied.size(), 7u);
  for (size_t k = 0; k < copied.size(); ++k) {
    EXPECT_EQ(copied[k].spec.get_string_attribute("oiio:subimagename"),
              original[k].spec.get_string_attribute("oiio:subimagename"));
    EXPECT_EQ(copied[k].spec.tile_width, 4);
    EXPECT_EQ(copied[k].spec.channelformats, original[k].spec.channelformats);
    EXPECT_EQ(std::memcmp(copied[k].pixels.data(), original[k].pixels.data(),
                          original[k].pixels.size() * sizeof(float)),
              0);
  }
}

// Known sRGB encodings (IEC 61966-2-1): linear 0.5 -> 0.7354 (code 188), 0.18 -> 0.4614 (118),
// 0.214 -> 0.5000 (127.5, rounds to 128), the linear segment's end 0.0031308 -> 0.04045 (10).
TEST(preview_writer, codes_follow_the_piecewise_srgb_curve_after_exposure_and_clamp) {
  EXPECT_EQ(preview_code(0.5f, 0.0), 188);
  EXPECT_EQ(preview_code(0.18f, 0.0), 118);
  EXPECT_EQ(preview_code(0.0031308f, 0.0), 10);
  EXPECT_EQ(preview_code(0.001f, 0.0), 3);   // 12.92 * 0.001 * 255 = 3.29
  EXPECT_EQ(preview_code(0.25f, 1.0), 188);  // one stop up: 0.5
  EXPECT_EQ(preview_code(1.0f, -1.0), 188);
  EXPECT_EQ(preview_code(1.0f, 0.0), 255);
  EXPECT_EQ(preview_code(7.0f, 0.0), 255);  // clamped
  EXPECT_EQ(preview_code(-2.0f, 0.0), 0);
  EXPECT_EQ(preview_code(std::nanf(""), 0.0), 0);
  EXPECT_EQ(preview_format("a/b.PNG"), "png");
  EXPECT_EQ(preview_format("b.jpeg"), "jpeg");
  EXPECT_EQ(preview_format("b.jpg"), "jpeg");
  EXPECT_EQ(preview_format("b.tif"), "");
}

TEST(exr_writer, unwritable_folder_is_an_io_error_and_leaves_nothing) {
  fs::path file = scratch_dir() / "missing_folder" / "out.exr";
  try {
    write_exr(file.string(), test_film(), exr_settings{}, exr_metadata{});
    FAIL() << "expected an error";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::io);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(file));
}

TEST(exr_writer, failed_write_keeps_the_previous_file_and_no_temporary) {
  fs::path dir = scratch_dir() / "keep";
  fs::create_directories(dir);
  fs::path file = dir / "out.exr";
  write_exr(file.string(), test_film(), exr_settings{}, exr_metadata{});
  auto size_before = fs::file_size(file);
  film empty;  // zero-size film: the writer must refuse it
  EXPECT_THROW(write_exr(file.string(), empty, exr_settings{}, exr_metadata{}), error);
  EXPECT_EQ(fs::file_size(file), size_before);
  size_t entries = 0;
  for (auto& entry : fs::directory_iterator(dir)) entries += entry.is_regular_file();
  EXPECT_EQ(entries, 1u);
}

}  // namespace
}  // namespace kiln
