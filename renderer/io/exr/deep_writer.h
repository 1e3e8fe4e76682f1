// Writes a deep image (render/deep_pixel.h) as a single-part deep scanline EXR through OpenEXR:
// per pixel its samples front to back, each with premultiplied R G B A, Z, ZBack and the ids
// (id.object, id.material, id.instance, id.crypto_object), all float. Written atomically like the
// flat EXR (a temporary file renamed into place).
#pragma once

#include <atomic>
#include <string>

#include "io/exr/exr_writer.h"
#include "render/deep_pixel.h"

namespace kiln {

// The channels of every deep file kiln writes, in the order they are stored per sample.
extern const char* const deep_channel_names[10];

// Writes deep to path with the header attributes of metadata (as the flat EXR has them), plus
// deepImageState (tidy where every pixel's samples are non-overlapping, else sorted) and
// kiln/deep_merge_tolerance. Throws kiln::error (io) on failure, (interrupted) when cancel is
// raised before the rename: then nothing is written.
void write_deep_exr(const std::string& path, const deep_image& deep, const exr_metadata& metadata,
                    const std::atomic<bool>* cancel = nullptr);

}  // namespace kiln
