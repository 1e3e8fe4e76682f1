#include "io/exr/exr_writer.h"

#include "core/error.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir() {
  fs::path dir = fs::temp_directory_path() / ("kiln_exr_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

film test_film() {
  film f(5, 3);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      size_t i = f.index(x, y);
      f.color[i] = vec4(0.25f * x, 0.5f * y, 1.0f / 3.0f, 1.0f);
      f.depth[i] = x == 0 ? inf : 1.0f + x + 10.0f * y;
      f.normal[i] = vec3(0.0f, 1.0f, 0.0f);
    }
  return f;
}

TEST(exr_writer, round_trips_channels_and_metadata) {
  fs::path file = scratch_dir() / "out.exr";
  exr_metadata metadata;
  metadata.world_to_camera[3][0] = 7.0;  // a translation, stored in the last row by OpenEXR
  metadata.attributes = {{"kiln/spp", "4"}};
  write_exr(file.string(), test_film(), exr_settings{true}, metadata);

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
  write_exr(file.string(), test_film(), exr_settings{false}, exr_metadata{});
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
  for (bool full_float : {false, true}) {
    fs::path file = scratch_dir() / (full_float ? "bright_float.exr" : "bright_half.exr");
    write_exr(file.string(), f, exr_settings{full_float}, exr_metadata{});
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    std::vector<float> pixels(5 * 3 * 8);
    ASSERT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, pixels.data()));
    const float* p = &pixels[(1 * 5 + 1) * 8];
    EXPECT_EQ(p[0], full_float ? 1e6f : 65504.0f);
    EXPECT_EQ(p[1], full_float ? -3e5f : -65504.0f);
    EXPECT_EQ(p[2], full_float ? 70000.0f : 65504.0f);
    EXPECT_EQ(p[3], 1.0f);
  }
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
