// The shot metadata as a compositor reads it: SMPTE time codes from frame counts (frame pairs above
// 30 fps, wrapping at 24 hours), framesPerSecond fractions (NTSC rates as N·1000/1001), and a
// written header read back through OpenEXR's own API with every attribute of its numeric type.
#include "io/exr/exr_shot_time.h"

#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFloatVectorAttribute.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "io/exr/exr_reader.h"
#include "io/exr/exr_writer.h"

namespace kiln {
namespace {

std::string text(const std::optional<smpte_time_code>& t) {
  if (!t) return "none";
  char out[32];
  std::snprintf(out, sizeof out, "%02d:%02d:%02d:%02d%s", t->hours, t->minutes, t->seconds, t->frame,
                t->field_phase ? "." : "");
  return out;
}

TEST(exr_shot_time, time_codes_count_frames_at_the_nominal_rate) {
  EXPECT_EQ(text(smpte_time_code_of(0, 24.0)), "00:00:00:00");
  EXPECT_EQ(text(smpte_time_code_of(23, 24.0)), "00:00:00:23");
  EXPECT_EQ(text(smpte_time_code_of(24, 24.0)), "00:00:01:00");
  EXPECT_EQ(text(smpte_time_code_of(49, 25.0)), "00:00:01:24");
  EXPECT_EQ(text(smpte_time_code_of(24 * 3661 + 5, 24.0)), "01:01:01:05");
  EXPECT_EQ(text(smpte_time_code_of(30 * 60, 30000.0 / 1001.0)), "00:01:00:00");  // non-drop: 30 a second
  EXPECT_EQ(text(smpte_time_code_of(24LL * 86400 + 2, 24.0)), "00:00:00:02");     // past 24 hours
  EXPECT_EQ(text(smpte_time_code_of(-1, 24.0)), "23:59:59:23");                   // before the first
}

TEST(exr_shot_time, rates_above_30_count_frame_pairs) {
  EXPECT_EQ(text(smpte_time_code_of(0, 60.0)), "00:00:00:00");
  EXPECT_EQ(text(smpte_time_code_of(1, 60.0)), "00:00:00:00.");
  EXPECT_EQ(text(smpte_time_code_of(59, 60.0)), "00:00:00:29.");
  EXPECT_EQ(text(smpte_time_code_of(60, 60.0)), "00:00:01:00");
  EXPECT_EQ(text(smpte_time_code_of(99, 50.0)), "00:00:01:24.");
  EXPECT_EQ(text(smpte_time_code_of(10, 120.0)), "none");
  EXPECT_EQ(text(smpte_time_code_of(10, 0.4)), "none");
}

TEST(exr_shot_time, frame_rates_are_fractions) {
  const auto rate = [](double fps) {
    const frame_rate_fraction r = frame_rate_of(fps);
    return std::to_string(r.numerator) + "/" + std::to_string(r.denominator);
  };
  EXPECT_EQ(rate(24.0), "24/1");
  EXPECT_EQ(rate(25.0), "25/1");
  EXPECT_EQ(rate(23.976), "24000/1001");
  EXPECT_EQ(rate(30000.0 / 1001.0), "30000/1001");
  EXPECT_EQ(rate(59.94), "60000/1001");
  EXPECT_EQ(rate(12.5), "25/2");
}

TEST(exr_shot_time, the_header_holds_numbers_and_the_shot_as_openexr_types) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("kiln_shot_" + std::to_string(::getpid()) + ".exr"))
          .string();
  film f(4, 2);
  exr_metadata metadata;
  metadata.attributes = {{"kiln/frame", 50},
                         {"kiln/fps", 25.0},
                         {"kiln/render_seconds", 1.5f},
                         {"kiln/shutter", vec2(-0.25f, 0.25f)},
                         {"kiln/background", vec3(0.1f, 0.2f, 0.3f)},
                         {"kiln/band_render_seconds", std::vector<float>{1, 2}},
                         {"kiln/camera", "main"}};
  metadata.shot = exr_shot_frame{25.0, 49};
  write_exr(path, f, exr_settings{}, metadata);

  Imf::InputFile in(path.c_str());
  const Imf::Header& h = in.header();
  ASSERT_TRUE(Imf::hasFramesPerSecond(h));
  EXPECT_EQ(Imf::framesPerSecondAttribute(h).value().n, 25);
  EXPECT_EQ(Imf::framesPerSecondAttribute(h).value().d, 1u);
  ASSERT_TRUE(Imf::hasTimeCode(h));
  const Imf::TimeCode& code = Imf::timeCodeAttribute(h).value();
  EXPECT_EQ(code.hours(), 0);
  EXPECT_EQ(code.minutes(), 0);
  EXPECT_EQ(code.seconds(), 1);
  EXPECT_EQ(code.frame(), 24);
  EXPECT_FALSE(code.dropFrame());
  ASSERT_NE(h.findTypedAttribute<Imf::IntAttribute>("kiln/frame"), nullptr);
  EXPECT_EQ(h.findTypedAttribute<Imf::IntAttribute>("kiln/frame")->value(), 50);
  ASSERT_NE(h.findTypedAttribute<Imf::DoubleAttribute>("kiln/fps"), nullptr);
  EXPECT_EQ(h.findTypedAttribute<Imf::DoubleAttribute>("kiln/fps")->value(), 25.0);
  ASSERT_NE(h.findTypedAttribute<Imf::FloatAttribute>("kiln/render_seconds"), nullptr);
  ASSERT_NE(h.findTypedAttribute<Imf::V2fAttribute>("kiln/shutter"), nullptr);
  EXPECT_EQ(h.findTypedAttribute<Imf::V2fAttribute>("kiln/shutter")->value(), Imath::V2f(-0.25f, 0.25f));
  ASSERT_NE(h.findTypedAttribute<Imf::V3fAttribute>("kiln/background"), nullptr);
  EXPECT_EQ(h.findTypedAttribute<Imf::V3fAttribute>("kiln/background")->value(),
            Imath::V3f(0.1f, 0.2f, 0.3f));
  ASSERT_NE(h.findTypedAttribute<Imf::FloatVectorAttribute>("kiln/band_render_seconds"), nullptr);
  EXPECT_EQ(h.findTypedAttribute<Imf::FloatVectorAttribute>("kiln/band_render_seconds")->value(),
            (std::vector<float>{1, 2}));
  ASSERT_NE(h.findTypedAttribute<Imf::StringAttribute>("kiln/camera"), nullptr);

  // A still is no frame of a shot: neither standard attribute.
  metadata.shot.reset();
  write_exr(path, f, exr_settings{}, metadata);
  Imf::InputFile still(path.c_str());
  EXPECT_FALSE(Imf::hasFramesPerSecond(still.header()));
  EXPECT_FALSE(Imf::hasTimeCode(still.header()));
  std::filesystem::remove(path);
}

// Changing an attribute to another type (a foreign file's string where kiln writes a number).
TEST(exr_shot_time, set_exr_attribute_replaces_one_of_another_type) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("kiln_retype_" + std::to_string(::getpid()) + ".exr"))
          .string();
  exr_metadata metadata;
  metadata.attributes = {{"kiln/render_seconds", "1.5"}};
  write_exr(path, film(2, 2), exr_settings{}, metadata);
  exr_image image = read_exr(path);
  set_exr_attribute(image, "kiln/render_seconds", 2.5f);
  EXPECT_EQ(exr_string_attribute(image, "kiln/render_seconds"), "");
  EXPECT_EQ(exr_float_attribute(image, "kiln/render_seconds"), 2.5f);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace kiln
