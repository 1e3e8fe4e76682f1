// Writes a film as one EXR file through OpenEXR itself: the film's AOVs (by default premultiplied
// RGBA plus Z and N) as layers, stored as exr_settings says (formats, codec, tiles, parts).
// The only module that knows EXR. Writes go to a temporary file beside the target that is
// renamed into place, so a failed write never leaves a partial image.
#pragma once

#include <array>
#include <atomic>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "io/exr/exr_beauty.h"
#include "io/exr/exr_reader.h"
#include "io/exr/exr_storage.h"
#include "io/exr/exr_value.h"
#include "render/film.h"

namespace kiln {

// What the header records besides the pixels.
struct exr_metadata {
  // OpenEXR's conventions (render/view_camera.h): camera space +X right, +Y up, +Z the viewing
  // direction; NDC (0, 0) at the display window's upper-left corner, (1, 1) at its lower-right.
  dmat4 world_to_camera{1.0};
  dmat4 world_to_ndc{1.0};
  // Written in this order, numbers as numbers: {"kiln/samples_per_pixel", 4},
  // {"renderTimeSeconds", 1.5f}, {"kiln/camera", "look-at"}.
  std::vector<std::pair<std::string, exr_value>> attributes;
  // A frame of a shot (--frame, --frames, --turntable): framesPerSecond and timeCode.
  std::optional<exr_shot_frame> shot;
  // The colour space of R G B (OpenEXR's chromaticities: red, green, blue, white as xy): Rec.709
  // primaries and D65 white, glTF's linear space, unless the render has a working space.
  std::array<float, 8> chromaticities{0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
};

// Throws kiln::error (io) when the directory of path does not exist or cannot be written.
// Called before rendering so a long render never ends in an unwritable path. probe_folder false
// skips creating a file in the folder (the caller has just done so for another file there: the
// frames of a sequence share a folder).
void check_output_writable(const std::string& path, bool probe_folder = true);

// Throws kiln::error (input, location "--compression") when settings would store an exact data layer
// of aovs (Z, P, ids) with a lossy codec: a single-part file has one codec for all its channels.
// Called before rendering; write_exr checks again.
void check_exr_settings(const aov_set& aovs, const exr_settings& settings);

// One layer of the file write_exr writes for a film, with the values as stored: its part name
// ("rgba", "depth", "N", ...), its channel names, and its samples row by row, channel-interleaved
// (height × width × channels), rounded to half where the layer is half. What a reader of the file
// gets back, bit for bit, under a lossless codec.
struct stored_layer {
  std::string name;
  std::vector<std::string> channels;
  bool half = false;
  std::vector<float> samples;
};
std::vector<stored_layer> stored_layers(const film& f, const exr_settings& settings);

// The beauty (R G B A) as write_exr stores it for the film: what read_exr_beauty reads back from
// the file, bit for bit, without reading it. Nullopt under a lossy codec (the file's values are
// the codec's) or without a beauty AOV.
std::optional<rgba_image> stored_beauty(const film& f, const exr_settings& settings);

// Writes the film to path atomically. Throws kiln::error (io) on failure, and (interrupted) when
// cancel is raised before the file is renamed into place: then nothing is written.
void write_exr(const std::string& path, const film& f, const exr_settings& settings,
               const exr_metadata& metadata, const std::atomic<bool>* cancel = nullptr);

// Writes an image read by read_exr (possibly with other pixels and data window) to path
// atomically, with its header, parts, compression, tiling and per-channel formats. Throws kiln::error (io) on
// failure.
void write_exr(const std::string& path, const exr_image& image);

}  // namespace kiln
