// Splits a frame into horizontal bands of whole pixel rows, so a render can be shared out to
// several processes or machines (`kiln render --tile i/N`) and stitched back (`kiln stitch`).
#pragma once

#include "render/film.h"

namespace kiln {

// Band `index` (0-based) of `count` bands over a width x height frame: rows
// [floor(index·height/count), floor((index+1)·height/count)), full width. Band heights differ by at
// most one row. Requires 0 <= index < count <= height, so every band holds at least one row.
pixel_rect frame_band(int index, int count, int width, int height);

}  // namespace kiln
