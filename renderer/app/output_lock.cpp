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

}  // namespace

output_folder_lock::output_folder_lock(const std::string& folder, bool wait)
    : path_((fs::path(folder) / output_lock_name).string()) {
  bool told = false;
  for (;;) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw io_error(path_, std::string("cannot create the lock file: ") + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      const std::string holder = held_by(fd);
      ::close(fd);
      if (e != EWOULDBLOCK) throw io_error(path_, std::string("cannot lock: ") + std::strerror(e));
      if (!wait)
        throw input_error(folder, "",
                          "the output folder is in use by " + holder +
                              "; wait for it to finish, give another --out-dir, or pass --wait-for-lock");
      if (!told)
        std::fprintf(stderr, "kiln batch: waiting for %s to release %s\n", holder.c_str(), folder.c_str());
      told = true;
      // Polled, not a blocking flock: the first SIGINT/SIGTERM must end the wait.
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (interrupt_requested())
        throw error(error_kind::interrupted, folder, "",
                    "interrupted while waiting for the output folder's lock");
      continue;
    }
    // The previous holder unlinks the file when it ends: a lock on the file it unlinked is no lock.
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) != 0 || ::stat(path_.c_str(), &named) != 0 || held.st_ino != named.st_ino ||
        held.st_dev != named.st_dev) {
      ::close(fd);
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
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still locked, so nobody takes a lock on a file about to go
  ::close(fd_);
}

void check_not_in_locked_folder(const std::string& path) {
  const fs::path target = fs::absolute(path).lexically_normal();
  for (fs::path folder = target.parent_path();; folder = folder.parent_path()) {
    const std::string lock = (folder / output_lock_name).string();
    const int fd = ::open(lock.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd >= 0) {
      const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
      const std::string holder = busy ? held_by(fd) : "";
      ::close(fd);
      if (busy)
        throw input_error(path, "",
                          "the folder " + folder.string() + " is the output folder of " + holder +
                              " that is still running; write elsewhere or wait for it");
    }
    if (folder == folder.parent_path()) break;
  }
}

}  // namespace kiln
