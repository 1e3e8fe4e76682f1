// OpenEXR's standard shot attributes from a frame rate and a frame: framesPerSecond as a fraction
// and an SMPTE 12M time code, never drop-frame. Plain numbers here; the header entries are made
// in io/exr/exr_base_header.cpp. Depends on core only.
#pragma once

#include <optional>

namespace kiln {

struct smpte_time_code {
  int hours = 0, minutes = 0, seconds = 0, frame = 0;
  bool field_phase = false;  // above 30 fps: the second frame of a pair
};

// The time code of the frame `frames` after the shot's first, which is 00:00:00:00, counted at the
// nominal rate round(fps) (30 for 29.97, as non-drop-frame time code counts). A time code's frame
// field holds 0-29, so rates above 30 count pairs of frames, as SMPTE 12M does at 50 and 60: the
// field is the pair's index and field_phase marks the second of the pair. Hours wrap at 24, and a
// frame before the first counts back from 24:00:00:00. Empty above 60 fps, which no time code counts.
std::optional<smpte_time_code> smpte_time_code_of(long long frames, double fps);

// fps as OpenEXR's framesPerSecond fraction: N·1000/1001 for the NTSC rates (23.976, 29.97, 47.952,
// 59.94, 119.88, given to 0.005), else OpenEXR's closest fraction (whole rates exactly).
struct frame_rate_fraction {
  int numerator = 24;
  unsigned denominator = 1;
};
frame_rate_fraction frame_rate_of(double fps);

}  // namespace kiln
