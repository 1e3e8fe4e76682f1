// The OpenImageIO side of exr_image, shared by the reader and the writer inside io/exr only.
#pragma once

#include <OpenImageIO/imageio.h>

#include "io/exr/exr_reader.h"

namespace kiln {

struct exr_header {
  OIIO::ImageSpec spec;
};

}  // namespace kiln
