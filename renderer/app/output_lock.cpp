#include "app/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <thread>
#include <utility>

#include "app/interrupt.h"
#include "core/error.h"

namespace kiln {

namespace fs = std::filesystem;

const char* const output_lock_name = ".kiln-batch.lock";

namespace {

// The holder writes its pid into the file once it has the lock; "" when unknown.
std::string holder_pid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid = n > 0 ? std::string(text, size_t(n)) : "";
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

std::string held_by(int fd) {
  const std::string pid = holder_pid(fd);
  return pid.empty() ? "another kiln batch" : "another kiln batch (pid " + pid + ")";
}

// Why what fd opened is not a lock file kiln made, "" when it is one: a regular file with no
// other name (a hard link would let the pid overwrite a file elsewhere) holding nothing but a pid
// (empty while its maker has not written it yet).
std::string not_a_lock_file(int fd) {
  struct stat s {};
  if (::fstat(fd, &s) != 0) return std::strerror(errno);
  if (!S_ISREG(s.st_mode)) return "the lock file is not a regular file";
  if (s.st_nlink != 1) return "the lock file has other names (hard links)";
  char text[33] = {};
  const ssize_t n = ::pread(fd, text, sizeof text, 0);
  const std::string pid = n > 0 ? std::string(text, size_t(n)) : "";
  if (n < 0 || pid.size() >= sizeof text || pid.find_first_not_of("0123456789\n") != std::string::npos)
    return "the lock file holds something other than a process id";
  return "";
}

// Opens the lock file at path, creating it when missing. The folder may be writable by others, so
// never through a symbolic link at the name (O_NOFOLLOW), never waiting on a FIFO (O_NONBLOCK), and
// never anything but a lock file kiln made: whatever else is there is refused and left as it is.
int open_lock_file(const std::string& path) {
  const std::string remedy =
      "; it is not one kiln made: remove it if no kiln batch is running, or give another --out-dir";
  const int fd =
      ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0644);
  if (fd < 0 && errno == ELOOP) throw input_error(path, "", "the lock file is a symbolic link" + remedy);
  if (fd < 0 && errno == EISDIR) throw input_error(path, "", "the lock file is a folder" + remedy);
  if (fd < 0) throw io_error(path, std::string("cannot create the lock file: ") + std::strerror(errno));
  const std::string problem = not_a_lock_file(fd);
  if (problem.empty()) return fd;
  ::close(fd);
  throw input_error(path, "", problem + remedy);
}

// Whether path still names the file fd holds: the previous holder unlinks the file when it ends,
// and a lock on a file it unlinked (or on one someone put in its place) is no lock.
bool names_file(const std::string& path, int fd) {
  struct stat held {
  }, named{};
  return ::fstat(fd, &held) == 0 && ::lstat(path.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
         held.st_dev == named.st_dev;
}

// Who holds the batch lock at lock ("another kiln batch (pid N)"), "" when nobody does. Only a
// regular file at the name itself is a lock: a link there is nobody's, and what it points to is
// not read.
std::string lock_holder(const std::string& lock) {
  const int fd = ::open(lock.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW | O_NOCTTY);
  if (fd < 0) return "";
  struct stat s {};
  const bool busy = ::fstat(fd, &s) == 0 && S_ISREG(s.st_mode) && ::flock(fd, LOCK_SH | LOCK_NB) != 0 &&
                    errno == EWOULDBLOCK;
  const std::string holder = busy ? held_by(fd) : "";
  ::close(fd);
  return holder;
}

// The nearest folder from `from` upward, stopping before `stop`, whose lock a running batch holds,
// and who holds it; an empty folder when none does.
std::pair<fs::path, std::string> locked_folder_above(const fs::path& from, const fs::path& stop) {
  for (fs::path folder = from; folder != stop; folder = folder.parent_path()) {
    if (std::string holder = lock_holder((folder / output_lock_name).string()); !holder.empty())
      return {folder, holder};
    if (folder == folder.parent_path()) break;
  }
  return {};
}

// Unlocks and removes a lock file this process made and holds.
void release(const std::string& path, int fd) {
  // While still locked, so nobody takes a lock on a file about to go; and only while the name is
  // still this file, so nothing someone put in its place is removed.
  if (names_file(path, fd)) ::unlink(path.c_str());
  ::close(fd);
}

}  // namespace

output_folder_lock::output_folder_lock(const std::string& folder, bool wait)
    : path_((fs::path(folder) / output_lock_name).string()) {
  bool told = false;
  // Refuses, or with wait tells once and pauses before the next try. Polled, not a blocking
  // flock: the first SIGINT/SIGTERM must end the wait.
  const auto refuse_or_wait = [&](const std::string& holder, const std::string& held,
                                  const std::string& why) {
    if (!wait)
      throw input_error(folder, "",
                        why + "; wait for it to finish, give another --out-dir, or pass --wait-for-lock");
    if (!told)
      std::fprintf(stderr, "kiln batch: waiting for %s to release %s\n", holder.c_str(), held.c_str());
    told = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (interrupt_requested())
      throw error(error_kind::interrupted, folder, "",
                  "interrupted while waiting for the output folder's lock");
  };
  for (;;) {
    const int fd = open_lock_file(path_);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      const std::string holder = held_by(fd);
      ::close(fd);
      if (e != EWOULDBLOCK) throw io_error(path_, std::string("cannot lock: ") + std::strerror(e));
      refuse_or_wait(holder, folder, "the output folder is in use by " + holder);
      continue;
    }
    if (!names_file(path_, fd)) {
      ::close(fd);
      continue;
    }
    // A lock covers its folder's subtree. Checked while holding this lock, so of two batches
    // locking a folder and one inside it at once, at least one sees the other.
    const fs::path here = fs::absolute(folder).lexically_normal();
    if (const auto [above, holder] = locked_folder_above(here.parent_path(), fs::path()); !above.empty()) {
      release(path_, fd);
      refuse_or_wait(holder, above.string(),
                     "the output folder lies inside " + above.string() + ", the output folder of " + holder +
                         " that is still running");
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
      // The pid is only for the message of whoever is refused; the lock itself holds.
    }
    fd_ = fd;
    return;
  }
}

output_folder_lock::~output_folder_lock() {
  if (fd_ >= 0) release(path_, fd_);
}

void check_not_in_locked_folder(const std::string& path, const std::string& own_folder) {
  const fs::path target = fs::absolute(path).lexically_normal();
  const fs::path stop = own_folder.empty() ? fs::path() : fs::absolute(own_folder).lexically_normal();
  const auto [folder, holder] = locked_folder_above(target.parent_path(), stop);
  if (!folder.empty())
    throw input_error(path, "",
                      "the folder " + folder.string() + " is the output folder of " + holder +
                          " that is still running; write elsewhere or wait for it");
}

}  // namespace kiln
