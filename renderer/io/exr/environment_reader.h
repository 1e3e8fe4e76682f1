// Reads an equirectangular environment image (OpenEXR, Radiance .hdr, or anything OpenImageIO
// reads, through the image codecs module) into a float RGBA kiln::image of linear radiance.
// Only io/* touch file formats.
#pragma once

#include <string>

#include "scene/scene.h"

namespace kiln {

// The largest environment file kiln reads: the largest map (2^27 texels) as float RGBA, with room
// for the file's header.
constexpr uint64_t max_environment_file_bytes = uint64_t(1) << 32;

// Throws kiln::error (input) naming the file and the reason when it cannot be read, and before
// opening it when the path names a FIFO, a device or a folder (an image reader would block on it
// or read forever) or a file over max_environment_file_bytes; (io) when the image codecs module
// cannot be loaded.
image read_environment_image(const std::string& path);

}  // namespace kiln
