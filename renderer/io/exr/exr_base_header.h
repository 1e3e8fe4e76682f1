// The header attributes every kiln EXR carries, flat or deep: windows, colour space, camera
// matrices, software, date and the render's metadata. Inside io/exr only.
#pragma once

#include <OpenEXR/ImfHeader.h>

#include "io/exr/exr_writer.h"
#include "render/film.h"

namespace kiln {

// The display window is frame (0, 0)-(width, height), the data window the stored region (they
// differ for crops); pixel aspect 1, screen window (0, 0) width 1, increasing y.
struct exr_frame_size {
  int width = 0, height = 0;
};
Imf::Header exr_base_header(const exr_frame_size& frame, const pixel_rect& stored,
                            const exr_metadata& metadata);

// Inserts name as the attribute type value holds (string, int, float, double, v2f, v3f,
// floatvector), replacing one of that name of any type.
void insert_exr_attribute(Imf::Header& header, const std::string& name, const exr_value& value);

}  // namespace kiln
