// Reads an equirectangular environment image (OpenEXR, Radiance .hdr, or anything OpenImageIO
// reads) into a float RGBA kiln::image of linear radiance. Only io/* touch file formats.
#pragma once

#include "scene/scene.h"

#include <string>

namespace kiln {

// Throws kiln::error (input) naming the file and the reason when it cannot be read.
image read_environment_image(const std::string& path);

}  // namespace kiln
