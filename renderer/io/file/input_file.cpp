#include "io/file/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "core/message_text.h"

namespace kiln {

namespace {

// What a stat() mode names, for a message that says what the path is instead of a file.
std::string kind_of(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

std::string problem_of(const struct stat& info, uint64_t max_bytes) {
  if (!S_ISREG(info.st_mode)) return "is " + kind_of(info.st_mode) + ", not a regular file";
  if (uint64_t(info.st_size) > max_bytes)
    return "is " + std::to_string(uint64_t(info.st_size)) + " bytes, over kiln's limit of " +
           std::to_string(max_bytes);
  return "";
}

// The error for path: named by the request's file and place; the path itself is quoted in the
// reason when the request names another file (the asset whose URI led here).
error refusal(error_kind kind, const std::string& path, const input_file_request& request,
              const std::string& reason) {
  const bool other = !request.file.empty() && request.file != path;
  return error(kind, other ? request.file : path, request.where, (other ? quoted(path) + " " : "") + reason);
}

// Closes the descriptor on every way out.
struct descriptor {
  int fd = -1;
  ~descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Reads a chunk at a time, so a raised cancel flag stops a read of gigabytes within milliseconds.
constexpr size_t chunk_bytes = size_t(1) << 20;

}  // namespace

std::string input_file_problem(const std::string& path, uint64_t max_bytes) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return "";  // missing or unreadable: the reader says which
  return problem_of(info, max_bytes);
}

bool input_file_missing(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) != 0 && (errno == ENOENT || errno == ENOTDIR);
}

namespace {

// An open regular file of known size.
struct open_file {
  descriptor file;
  uint64_t size = 0;
};

// Checks path with stat() before opening it (opening some devices has effects, and a FIFO would
// wait for a writer), opens it with O_NONBLOCK (should the path have become a FIFO since, open()
// returns at once) and checks again with fstat().
void open_checked(const std::string& path, const input_file_request& request, open_file& out) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw refusal(error_kind::input, path, request, std::string("cannot open file: ") + std::strerror(errno));
  if (std::string why = problem_of(info, request.max_bytes); !why.empty())
    throw refusal(error_kind::input, path, request, why);
  out.file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (out.file.fd < 0)
    throw refusal(error_kind::input, path, request, std::string("cannot open file: ") + std::strerror(errno));
  if (::fstat(out.file.fd, &info) != 0)
    throw refusal(error_kind::io, path, request, std::string("cannot read file: ") + std::strerror(errno));
  if (std::string why = problem_of(info, request.max_bytes); !why.empty())
    throw refusal(error_kind::input, path, request, why);
  // A regular file: blocking reads are what its file system expects.
  const int flags = ::fcntl(out.file.fd, F_GETFL);
  if (flags >= 0) ::fcntl(out.file.fd, F_SETFL, flags & ~O_NONBLOCK);
  out.size = uint64_t(info.st_size);
}

void throw_if_cancelled(const std::string& path, const input_file_request& request) {
  if (request.cancel && request.cancel->load(std::memory_order_relaxed))
    throw refusal(error_kind::interrupted, path, request, "interrupted while reading, nothing written");
}

// Reads up to the size fstat() gave: a file that grows while it is read (or a /proc file that
// claims size 0 and would block) cannot make the read go on. A file that shrinks gives fewer bytes.
void read_open_file(const std::string& path, const input_file_request& request, open_file& in,
                    const std::function<void(const char* bytes, size_t count)>& consume) {
  uint64_t left = in.size;
  std::vector<char> buffer(size_t(std::min<uint64_t>(left, chunk_bytes)));
  while (left > 0) {
    throw_if_cancelled(path, request);
    const ssize_t got = ::read(in.file.fd, buffer.data(), size_t(std::min<uint64_t>(left, buffer.size())));
    if (got < 0 && errno == EINTR) continue;  // a signal: the flag check above decides
    if (got < 0)
      throw refusal(error_kind::io, path, request, std::string("cannot read file: ") + std::strerror(errno));
    if (got == 0) break;
    consume(buffer.data(), size_t(got));
    left -= uint64_t(got);
  }
  throw_if_cancelled(path, request);
}

}  // namespace

void read_input_file(const std::string& path, const input_file_request& request,
                     const std::function<void(const char* bytes, size_t count)>& consume) {
  open_file in;
  open_checked(path, request, in);
  read_open_file(path, request, in, consume);
}

std::vector<uint8_t> read_whole_input_file(const std::string& path, const input_file_request& request) {
  open_file in;
  open_checked(path, request, in);
  std::vector<uint8_t> bytes;
  bytes.reserve(size_t(in.size));
  read_open_file(path, request, in, [&bytes](const char* data, size_t count) {
    bytes.insert(bytes.end(), reinterpret_cast<const uint8_t*>(data),
                 reinterpret_cast<const uint8_t*>(data) + count);
  });
  return bytes;
}

}  // namespace kiln
