#include "io/exr/atomic_write.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// Flushes a closed file's data to the disk. The writer has closed its descriptor, so the
// file is opened again: fsync on any descriptor of the file syncs its data. Without this a crash
// right after the rename can leave the target name pointing at an empty or partial file.
bool sync_to_disk(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  return ::close(fd) == 0 && ok;
}

// The temporary files being written, for remove_temporary_files_in_progress: a fixed table of
// paths a signal handler can read without locks. A slot is free (0), being filled (1) or holds
// a path (2).
constexpr int slot_count = 8;
constexpr size_t slot_bytes = 4096;
char slot_paths[slot_count][slot_bytes];
std::atomic<int> slot_state[slot_count];
static_assert(std::atomic<int>::is_always_lock_free);

// Holds a slot for one temporary file while it exists; none when the table is full or the path
// too long (the file is then only cleaned up by the next run, as after SIGKILL).
class registration {
 public:
  explicit registration(const std::string& path) {
    if (path.size() >= slot_bytes) return;
    for (int i = 0; i < slot_count; ++i) {
      int expected = 0;
      if (!slot_state[i].compare_exchange_strong(expected, 1)) continue;
      std::memcpy(slot_paths[i], path.c_str(), path.size() + 1);
      slot_state[i].store(2);
      slot_ = i;
      return;
    }
  }
  ~registration() {
    if (slot_ >= 0) slot_state[slot_].store(0);
  }
  registration(const registration&) = delete;
  registration& operator=(const registration&) = delete;

 private:
  int slot_ = -1;
};

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || !name[0]) return "host";
  std::string host(name);
  for (char& c : host)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_') c = '_';
  return host;
}

// Removes ".NAME.tmp-HOST-PID" files in folder whose HOST is this one and whose PID names no
// process: what a SIGKILL during a write leaves. Another host's files are never touched (a farm
// writes into shared folders from many hosts, and their PIDs mean nothing here).
void remove_stale_temporaries(const fs::path& folder) {
  const std::string marker = ".tmp-" + host_name() + "-";
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const size_t at = name.rfind(marker);
    if (name.empty() || name[0] != '.' || at == std::string::npos) continue;
    const std::string digits = name.substr(at + marker.size());
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const pid_t pid = pid_t(std::stol(digits));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
}

}  // namespace

std::string temporary_path(const std::string& path) {
  fs::path target(path);
  std::string name =
      "." + target.filename().string() + ".tmp-" + host_name() + "-" + std::to_string(::getpid());
  return (target.parent_path() / name).string();
}

void remove_temporary_files_in_progress() {
  for (int i = 0; i < slot_count; ++i)
    if (slot_state[i].load() == 2) ::unlink(slot_paths[i]);
}

void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const std::string& temporary)>& write,
                      const std::atomic<bool>* cancel) {
  const std::string temporary = temporary_path(path);
  remove_stale_temporaries(fs::path(path).parent_path().empty() ? fs::path(".")
                                                                : fs::path(path).parent_path());
  const registration registered(temporary);
  std::string reason;
  try {
    reason = write(temporary);
  } catch (...) {
    std::error_code ec;
    fs::remove(temporary, ec);
    throw;
  }
  bool ok = reason.empty();
  if (ok && cancel && cancel->load()) {
    std::error_code ec;
    fs::remove(temporary, ec);
    throw error(error_kind::interrupted, path, "", "interrupted while writing, nothing written");
  }
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
