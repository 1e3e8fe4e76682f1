// Writes an image file through OpenImageIO so that a failed write never leaves a partial file:
// a temporary file beside the target, fsynced, then renamed into place. Inside io/exr only.
#pragma once

#include <OpenImageIO/imageio.h>

#include <functional>
#include <string>

namespace kiln {

// The temporary name write_atomically uses for path: hidden, beside it (so the rename stays on one
// file system), unique to this process.
std::string temporary_path(const std::string& path);

// Creates an OpenImageIO writer for format (e.g. "openexr", "png"), lets write open, fill and
// close it on the temporary path it is given (returning false on failure, with the reason in the
// writer's geterror()), then flushes and renames. Throws kiln::error (io) on failure, leaving no
// temporary file behind and any earlier file at path untouched.
void write_atomically(const std::string& path, const std::string& format,
                      const std::function<bool(OIIO::ImageOutput& out, const std::string& temporary)>& write);

}  // namespace kiln
