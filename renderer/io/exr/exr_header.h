// The OpenImageIO side of exr_image, shared by the reader and the writer inside io/exr only.
#pragma once

#include <OpenImageIO/imageio.h>

#include <vector>

#include "io/exr/exr_reader.h"

namespace kiln {

// One OpenImageIO spec per part of the file (one for a single-part file), in file order; each
// holds its attributes, channel formats, compression and tiling. exr_image's channels are these
// parts' channels one after another.
struct exr_header {
  std::vector<OIIO::ImageSpec> parts;
};

}  // namespace kiln
