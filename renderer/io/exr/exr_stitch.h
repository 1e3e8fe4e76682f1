// Joins region images (e.g. the bands of `kiln render --tile i/N`) into one full frame without
// converting a pixel: each channel keeps its own format.
#pragma once

#include <string>
#include <vector>

#include "io/exr/exr_reader.h"

namespace kiln {

class memory_budget;

// The full-frame image made of regions[k] (read from paths[k]), with the header of the first, except
// renderTimeSeconds, the sum of the regions' (each region's own in kiln/band_render_seconds). The
// regions must share the display window and the channel list (names and formats), lie inside the
// display window, not overlap and together cover it; otherwise throws kiln::error (input) naming
// the file and the problem. The frame's pixels are charged to budget (when given) before they are
// made.
exr_image stitch_regions(const std::vector<std::string>& paths, const std::vector<exr_image>& regions,
                         memory_budget* budget = nullptr);

}  // namespace kiln
