// Writes a file so that a failed write never leaves a partial file: a temporary file beside the
// target, fsynced, then renamed into place. Format-neutral (EXR, PNG, ...); inside io/ only.
#pragma once

#include <atomic>
#include <functional>
#include <string>

namespace kiln {

// The temporary name write_atomically uses for path: hidden, beside it (so the rename stays on one
// file system), naming this host and process: ".NAME.tmp-HOST-PID".
std::string temporary_path(const std::string& path);

// write(temporary) writes the whole file at `temporary` and returns "" or the reason it failed
// (or throws). `what` names the format in the error ("EXR", "PNG"). Then flushes the file to disk
// and renames it to path. Throws kiln::error (io) "cannot write <what>: <reason>" on failure, and
// (interrupted) when cancel is raised before the rename, leaving no temporary file behind and any
// earlier file at path untouched. First removes the temporary files that processes of this host
// which no longer exist left in path's folder (killed while writing).
void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const std::string& temporary)>& write,
                      const std::atomic<bool>* cancel = nullptr);

// Unlinks the temporary files write_atomically is writing right now. Async-signal-safe: for a
// signal handler about to end the process, so no temporary file outlives it.
void remove_temporary_files_in_progress();

}  // namespace kiln
