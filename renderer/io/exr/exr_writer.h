// Writes a film as one OpenEXR file through OpenImageIO: the film's AOVs (by default premultiplied
// RGBA plus Z and N).
// The only module that knows EXR. Writes go to a temporary file beside the target that is
// renamed into place, so a failed write never leaves a partial image.
#pragma once

#include "core/math.h"
#include "io/exr/exr_reader.h"
#include "render/film.h"

#include <string>
#include <utility>
#include <vector>

namespace kiln {

struct exr_settings {
  // RGBA, N, albedo and uv as 32-bit float; half otherwise. Z, P, ids and Cryptomatte are always float.
  bool full_float = false;
};

// What the header records besides the pixels.
struct exr_metadata {
  dmat4 world_to_camera{1.0};  // camera space: +X right, +Y up, looking along -Z
  dmat4 world_to_ndc{1.0};
  std::vector<std::pair<std::string, std::string>> attributes;  // e.g. {"kiln/spp", "4"}
  std::vector<std::pair<std::string, float>> float_attributes;  // e.g. {"renderTimeSeconds", 1.5f}
  std::vector<std::pair<std::string, int>> int_attributes;      // e.g. {"samplesPerPixel", 4}
};

// Throws kiln::error (io) when the directory of path does not exist or cannot be written.
// Called before rendering so a long render never ends in an unwritable path.
void check_output_writable(const std::string& path);

// Writes the film to path atomically. Throws kiln::error (io) on failure.
void write_exr(const std::string& path, const film& f, const exr_settings& settings,
               const exr_metadata& metadata);

// Writes an image read by read_exr (possibly with other pixels and data window) to path
// atomically, with its header and per-channel formats. Throws kiln::error (io) on failure.
void write_exr(const std::string& path, const exr_image& image);

}  // namespace kiln
