// The value of one EXR header attribute as kiln writes it: text, or a number the way OpenEXR
// stores numbers (int, float, double, v2f, v3f, a float vector), so that Nuke and oiiotool read
// numbers where they are numbers. Depends on core only.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "core/math.h"

namespace kiln {

using exr_value = std::variant<std::string, int, float, double, vec2, vec3, std::vector<float>>;

// The frame of a shot that a render is: OpenEXR's standard framesPerSecond and timeCode are
// written from it (io/exr/exr_shot_time.h).
struct exr_shot_frame {
  double fps = 24.0;
  long long frames_since_start = 0;  // the frame's number less the shot's first (its time 0)
};

}  // namespace kiln
