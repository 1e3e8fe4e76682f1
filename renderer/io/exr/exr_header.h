// The OpenEXR side of exr_image, shared by the reader and the writer inside io/exr only.
#pragma once

#include <OpenEXR/ImfHeader.h>

#include <vector>

#include "io/exr/exr_reader.h"

namespace kiln {

// One OpenEXR header per part of the file (one for a single-part file), in file order; each holds
// its attributes, channel list, compression and tiling. exr_image's channels are these parts'
// channels one after another, each part's in its channel list's (alphabetical) order.
struct exr_header {
  std::vector<Imf::Header> parts;
};

}  // namespace kiln
