// --frames ranges and frame output patterns: what each form parses to, what is refused, and how
// #### and %0Nd fill in (only in the file name, the last placeholder winning).
#include "job/frame_range.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace kiln {
namespace {

TEST(frame_range, ranges_steps_single_and_negative_frames_parse) {
  EXPECT_EQ(frame_numbers(parse_frame_range("1-5")), (std::vector<long long>{1, 2, 3, 4, 5}));
  EXPECT_EQ(frame_numbers(parse_frame_range("1-10:4")), (std::vector<long long>{1, 5, 9}));
  EXPECT_EQ(frame_numbers(parse_frame_range("12")), (std::vector<long long>{12}));
  EXPECT_EQ(frame_numbers(parse_frame_range("-3--1")), (std::vector<long long>{-3, -2, -1}));
  EXPECT_EQ(frame_numbers(parse_frame_range("-2-1")), (std::vector<long long>{-2, -1, 0, 1}));
}

TEST(frame_range, bad_ranges_are_refused_naming_the_option) {
  for (const char* text : {"", "a-b", "1-", "1-5:", "1-5:0", "5-1", "1,2,3", "1-2000000:1", "1 - 5"}) {
    SCOPED_TRACE(text);
    try {
      parse_frame_range(text);
      ADD_FAILURE() << "accepted";
    } catch (const error& e) {
      EXPECT_EQ(e.kind(), error_kind::input);
      EXPECT_EQ(e.location(), "--frames");
    }
  }
}

TEST(frame_range, placeholders_fill_in_the_file_name_only) {
  EXPECT_EQ(frame_path("shot.####.exr", 7), "shot.0007.exr");
  EXPECT_EQ(frame_path("shot.#.exr", 123), "shot.123.exr");
  EXPECT_EQ(frame_path("shot_%04d.exr", 42), "shot_0042.exr");
  EXPECT_EQ(frame_path("shot_%d.exr", 42), "shot_42.exr");
  EXPECT_EQ(frame_path("shot.####.exr", -3), "shot.-003.exr");
  EXPECT_EQ(frame_path("take#2/shot.###.exr", 5), "take#2/shot.005.exr");
  EXPECT_EQ(frame_path("a_%02d.####.exr", 9), "a_%02d.0009.exr");  // the last placeholder counts
  EXPECT_EQ(frame_path("plain.exr", 9), "plain.exr");
  EXPECT_TRUE(has_frame_placeholder("s.####.exr"));
  EXPECT_TRUE(has_frame_placeholder("s.%03d.exr"));
  EXPECT_FALSE(has_frame_placeholder("take#2/shot.exr"));
  EXPECT_FALSE(has_frame_placeholder("s.%s.exr"));
}

}  // namespace
}  // namespace kiln
