// Writes a file so that a failed write never leaves a partial file: a temporary file beside the
// target, fsynced, then renamed into place. Format-neutral (EXR, PNG, ...); inside io/ only.
#pragma once

#include <functional>
#include <string>

namespace kiln {

// The temporary name write_atomically uses for path: hidden, beside it (so the rename stays on one
// file system), unique to this process.
std::string temporary_path(const std::string& path);

// write(temporary) writes the whole file at `temporary` and returns "" or the reason it failed.
// `what` names the format in the error ("EXR", "PNG"). Then flushes the file to disk and renames
// it to path. Throws kiln::error (io) "cannot write <what>: <reason>" on failure, leaving no
// temporary file behind and any earlier file at path untouched.
void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const std::string& temporary)>& write);

}  // namespace kiln
