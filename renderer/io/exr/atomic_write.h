// Writes a file so that a failed write never leaves a partial file: a temporary file beside the
// target, fsynced, then renamed into place. Knows no image library: the caller's writer fills the
// temporary file. Inside io/exr and the image codecs module only.
#pragma once

#include <functional>
#include <string>

namespace kiln {

// The temporary name write_atomically uses for path: hidden, beside it (so the rename stays on one
// file system), unique to this process.
std::string temporary_path(const std::string& path);

// Lets write create and fill the whole file at the temporary path it is given (returning "" on
// success, else the reason it failed), then flushes and renames it to path. `what` names the
// format in the error ("EXR", "PNG"). Throws kiln::error (io) on failure, leaving no temporary
// file behind and any earlier file at path untouched.
void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const std::string& temporary)>& write);

}  // namespace kiln
