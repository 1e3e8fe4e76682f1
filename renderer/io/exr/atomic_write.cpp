#include "io/exr/atomic_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// Flushes a closed file's data to the disk. Image writers do not expose their descriptor, so the
// file is opened again: fsync on any descriptor of the file syncs its data. Without this a crash
// right after the rename can leave the target name pointing at an empty or partial file.
bool sync_to_disk(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  return ::close(fd) == 0 && ok;
}

}  // namespace

std::string temporary_path(const std::string& path) {
  fs::path target(path);
  std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid());
  return (target.parent_path() / name).string();
}

void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const std::string& temporary)>& write) {
  const std::string temporary = temporary_path(path);
  std::string reason = write(temporary);
  bool ok = reason.empty();
  if (ok && !sync_to_disk(temporary, O_RDONLY)) {
    ok = false;
    reason = "cannot flush the file to disk";
  }
  std::error_code ec;
  if (ok) fs::rename(temporary, path, ec);
  // The rename itself lives in the folder: sync it too, best effort (some file systems refuse).
  if (ok && !ec)
    sync_to_disk(fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string(),
                 O_RDONLY | O_DIRECTORY);
  if (!ok || ec) {
    fs::remove(temporary, ec);
    throw io_error(path,
                   "cannot write " + what + ": " + (reason.empty() ? std::string("rename failed") : reason));
  }
}

}  // namespace kiln
