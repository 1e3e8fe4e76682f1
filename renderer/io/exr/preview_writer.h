// Writes an 8-bit PNG or JPEG preview of an EXR's beauty for people to look at, through a fixed,
// documented view transform (preview_codes.h) or an OpenColorIO display/view. The EXR is read
// through OpenEXR and the picture encoded by libpng or libjpeg in kiln itself, so a preview never
// opens the image codecs module; depends on core, the EXR reader and io/image_codecs' direct codecs.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "io/colour/colour_module.h"
#include "io/exr/exr_beauty.h"
#include "io/exr/preview_codes.h"

namespace kiln {

// Reads R, G, B, A (premultiplied) from the EXR at exr_path (the first part holding all four, in a
// multi-part file) and writes preview_path atomically. A PNG holds straight colour, R G B divided
// by A where A > 0, through preview_code, and A as round(255 · clamp(A, 0, 1)); a JPEG holds the
// premultiplied R G B through preview_code (the colour over black) and no alpha. The preview covers
// the EXR's data window. Throws kiln::error (input) when the EXR has no R G B A, (io) when the
// preview cannot be written, (interrupted) when cancel is raised before it is renamed into place.
// With view, the colour (times 2^exposure) goes through that display transform instead of
// preview_code, and its code values are round(255 · clamp(v, 0, 1)).
void write_preview(const std::string& exr_path, const std::string& preview_path, double exposure,
                   const display_transform* view = nullptr, const std::atomic<bool>* cancel = nullptr);

// The same for a beauty already in memory (premultiplied R G B A over the data window, as the EXR
// stores it: io/exr/exr_writer.h's stored_beauty), without reading the file back.
void write_preview(const rgba_image& beauty, const std::string& preview_path, double exposure,
                   const display_transform* view = nullptr, const std::atomic<bool>* cancel = nullptr);

// Writes width x height 8-bit code values (row 0 at the top; channels 3, R G B, or 4, R G B and
// straight A; a JPEG drops A) as the PNG or JPEG path's extension names, atomically. Throws
// kiln::error (input) for another extension, (io) when the file cannot be written, (interrupted)
// as write_preview.
void write_preview_image(const std::string& path, int width, int height, int channels,
                         const std::vector<unsigned char>& codes, const std::atomic<bool>* cancel = nullptr);

// True when preview_path is a complete preview of a width x height data window: its format is the
// one its extension names, its size is right, it ends with the format's closing marker (PNG IEND,
// JPEG EOI: a truncated JPEG otherwise decodes as grey) and every pixel decodes without a libpng
// or libjpeg error or warning.
bool preview_complete(const std::string& preview_path, int width, int height);

}  // namespace kiln
