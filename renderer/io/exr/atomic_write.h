// Writes a file so that a failed write never leaves a partial file: a temporary file beside the
// target, fsynced, then renamed into place. Format-neutral (EXR, PNG, JSON reports): io/ and the
// CLI's text reports use it; it depends on the standard library and POSIX only.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>

namespace kiln {

// The temporary file of one write: its name, and a descriptor open for writing that stays the
// caller's (write_atomically's) to sync and close.
struct temporary_file {
  std::string path;
  int fd = -1;
};

// Creates a new, empty file beside path for one write: hidden, on path's file system (so the
// rename is atomic), named ".NAME.kiln-tmp-HOST-PID-N" with N counting this process's temporary
// files, so no two writes (threads included) ever share one. Created with O_EXCL: never an
// existing file or a link someone placed at the name. Returns its descriptor, or -1 with errno
// set; temporary receives its name.
int create_temporary_file(const std::string& path, std::string& temporary);

// write(temporary) writes the whole file through temporary.fd (or a dup of it; never closing
// it) and returns "" or the reason it failed (or throws). `what` names the format in the error
// ("EXR", "PNG"). Then flushes the file to disk and renames it to path: concurrent writes of one
// path leave exactly one complete file. Throws kiln::error (io) "cannot write <what>: <reason>" on
// failure, and (interrupted) when cancel is raised before the rename, leaving no temporary file
// behind and any earlier file at path untouched. First removes the temporary files of path that
// processes of this host which no longer exist left (killed while writing; older kiln's
// ".NAME.tmp-HOST-PID" included), and nothing else.
void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const temporary_file& temporary)>& write,
                      const std::atomic<bool>* cancel = nullptr);

// Writes size bytes to fd, retrying short writes and EINTR; "" or the reason it failed.
std::string write_all(int fd, const void* data, size_t size);

// Unlinks the temporary files write_atomically is writing right now. Async-signal-safe: for a
// signal handler about to end the process, so no temporary file outlives it.
void remove_temporary_files_in_progress();

}  // namespace kiln
