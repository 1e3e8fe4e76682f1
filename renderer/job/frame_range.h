// The frames of a shot (--frames FIRST-LAST[:STEP]) and the output file of each: a pattern with
// a run of '#' (padded to its length, as Nuke and Blender write it) or a printf-style %d / %0Nd.
#pragma once

#include <string>
#include <vector>

namespace kiln {

// The most frames one --frames may name: far past any shot, and bounded memory for the list.
constexpr long long max_sequence_frames = 1000000;

struct frame_range {
  long long first = 1;
  long long last = 1;
  long long step = 1;
};

// "1-240", "1-240:2", "12", "-10--1"; throws kiln::error (input, location --frames) for anything
// else, a last frame before the first, a step below 1 or more than max_sequence_frames frames.
frame_range parse_frame_range(const std::string& text);

// first, first + step, ... up to last.
std::vector<long long> frame_numbers(const frame_range& range);

// Whether the pattern holds a frame placeholder (#### or %d / %0Nd).
bool has_frame_placeholder(const std::string& pattern);

// The pattern with its placeholder replaced by the frame number ("shot.####.exr", 7 ->
// "shot.0007.exr"; "%03d" -> "007"); a pattern without one comes back unchanged. Only the last
// run of '#' (or the last %d) in the file name counts, so a folder named "#1" is left alone.
std::string frame_path(const std::string& pattern, long long frame);

}  // namespace kiln
