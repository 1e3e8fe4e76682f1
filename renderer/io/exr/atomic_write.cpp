#include "io/exr/atomic_write.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// Flushes the rename in path's folder to the disk, best effort (some file systems refuse).
void sync_folder_of(const std::string& path) {
  const std::string folder =
      fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string();
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
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
// too long (the file is then only cleaned up by the next write of its target, as after SIGKILL).
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

// Closes a descriptor when the write ends, however it ends.
struct descriptor_guard {
  int fd;
  ~descriptor_guard() { ::close(fd); }
};

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || !name[0]) return "host";
  std::string host(name);
  for (char& c : host)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_') c = '_';
  return host;
}

// ".NAME.kiln-tmp-HOST-": what every temporary file of path on this host begins with.
std::string temporary_prefix(const std::string& path) {
  return "." + fs::path(path).filename().string() + ".kiln-tmp-" + host_name() + "-";
}

// ".NAME.tmp-HOST-": what the one temporary file of path a process of this host wrote began with
// before kiln numbered them (".NAME.tmp-HOST-PID"). A killed older kiln left such files.
std::string legacy_temporary_prefix(const std::string& path) {
  return "." + fs::path(path).filename().string() + ".tmp-" + host_name() + "-";
}

bool all_digits(const std::string& s, size_t most) {
  return !s.empty() && s.size() <= most && s.find_first_not_of("0123456789") == std::string::npos;
}

// The process id in name when name is exactly prefix + "PID-N" (numbered) or prefix + "PID"
// (not); 0 otherwise.
pid_t writer_of(const std::string& name, const std::string& prefix, bool numbered) {
  if (name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string rest = name.substr(prefix.size());
  const size_t dash = numbered ? rest.find('-') : rest.size();
  if (dash == std::string::npos || !all_digits(rest.substr(0, dash), 9) ||
      (numbered && !all_digits(rest.substr(dash + 1), 20)))
    return 0;
  return pid_t(std::stol(rest.substr(0, dash)));
}

// Removes the temporary files of path that a process of this host left and no longer runs: what
// a SIGKILL during a write leaves. Only what kiln can prove its own goes: the exact name of a
// temporary file of this very path, a regular file (never a link) of this user. Another host's
// files are never touched (a farm writes into shared folders from many hosts, and their PIDs mean
// nothing here), nor a name kiln would not have made (a user's ".notes.tmp-HOST-PID"). Older
// kiln's unnumbered name for this path counts as its own too, by the same rules.
void remove_dead_temporaries(const std::string& path) {
  const fs::path folder = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  const std::string prefix = temporary_prefix(path), legacy_prefix = legacy_temporary_prefix(path);
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const pid_t pid = std::max(writer_of(name, prefix, true), writer_of(name, legacy_prefix, false));
    if (pid <= 0 || pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH)
      continue;  // alive, or not ours
    struct stat s {};
    if (::lstat(it->path().c_str(), &s) != 0 || !S_ISREG(s.st_mode) || s.st_uid != ::geteuid()) continue;
    ::unlink(it->path().c_str());
  }
}

// Numbers this process's temporary files: with the pid, a name no other write has.
std::atomic<unsigned long> temporary_count{0};

}  // namespace

int create_temporary_file(const std::string& path, std::string& temporary) {
  const fs::path folder = fs::path(path).parent_path();
  const std::string prefix = temporary_prefix(path) + std::to_string(::getpid()) + "-";
  // A name can be taken by a file an earlier process with this pid left, or by another copy of this
  // code in the process (the image codecs module counts on its own): then the next number.
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = (folder / (prefix + std::to_string(temporary_count.fetch_add(1)))).string();
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;  // errno is EEXIST
}

std::string write_all(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  for (size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return n < 0 ? std::strerror(errno) : "nothing written";
    done += size_t(n);
  }
  return "";
}

void remove_temporary_files_in_progress() {
  for (int i = 0; i < slot_count; ++i)
    if (slot_state[i].load() == 2) ::unlink(slot_paths[i]);
}

void write_atomically(const std::string& path, const std::string& what,
                      const std::function<std::string(const temporary_file& temporary)>& write,
                      const std::atomic<bool>* cancel) {
  remove_dead_temporaries(path);
  temporary_file temporary;
  temporary.fd = create_temporary_file(path, temporary.path);
  if (temporary.fd < 0)
    throw io_error(path, "cannot write " + what + ": cannot create the file (" + std::strerror(errno) + ")");
  const descriptor_guard closed_at_end{temporary.fd};
  const registration registered(temporary.path);
  std::string reason;
  try {
    reason = write(temporary);
  } catch (...) {
    ::unlink(temporary.path.c_str());
    throw;
  }
  if (reason.empty() && cancel && cancel->load()) {
    ::unlink(temporary.path.c_str());
    throw error(error_kind::interrupted, path, "", "interrupted while writing, nothing written");
  }
  // Without the fsync a crash right after the rename can leave path naming an empty or partial file.
  if (reason.empty() && ::fsync(temporary.fd) != 0)
    reason = std::string("cannot flush the file to disk (") + std::strerror(errno) + ")";
  if (reason.empty() && ::rename(temporary.path.c_str(), path.c_str()) != 0)
    reason = std::string("cannot rename the finished file into place (") + std::strerror(errno) + ")";
  if (!reason.empty()) {
    ::unlink(temporary.path.c_str());
    throw io_error(path, "cannot write " + what + ": " + reason);
  }
  sync_folder_of(path);
}

}  // namespace kiln
