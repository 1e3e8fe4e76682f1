#include "io/exr/exr_file_stream.h"

#include <OpenEXR/Iex.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace kiln {

exr_file_stream::exr_file_stream(int fd, const std::string& path) : Imf::OStream(path.c_str()) {
  // A duplicate, so that closing the stream leaves fd to its owner, who syncs it; close-on-exec,
  // like every descriptor kiln opens. Never the path: what is at the name may have changed since.
  const int own = ::fcntl(fd, F_DUPFD_CLOEXEC, 0);
  file_ = own < 0 ? nullptr : ::fdopen(own, "wb");
  if (file_) return;
  error_ = std::string("cannot open the file (") + std::strerror(errno) + ")";
  if (own >= 0) ::close(own);
}

exr_file_stream::~exr_file_stream() {
  if (file_) std::fclose(file_);
}

void exr_file_stream::fail(const char* what) {
  const std::string reason = std::string(what) + " (" + std::strerror(errno) + ")";
  if (error_.empty()) error_ = reason;
  throw IEX_NAMESPACE::IoExc(reason);
}

void exr_file_stream::write(const char c[], int n) {
  if (!file_) throw IEX_NAMESPACE::IoExc(error_);
  if (n > 0 && std::fwrite(c, 1, size_t(n), file_) != size_t(n)) fail("cannot write the file");
}

uint64_t exr_file_stream::tellp() {
  if (!file_) throw IEX_NAMESPACE::IoExc(error_);
  const off_t position = ::ftello(file_);
  if (position < 0) fail("cannot tell the file position");
  return uint64_t(position);
}

void exr_file_stream::seekp(uint64_t pos) {
  if (!file_) throw IEX_NAMESPACE::IoExc(error_);
  if (::fseeko(file_, off_t(pos), SEEK_SET) != 0) fail("cannot seek in the file");
}

std::string exr_file_stream::close() {
  if (file_) {
    const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
    const int flush_errno = errno;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (error_.empty() && !(flushed && closed))
      error_ = std::string("cannot write the file (") + std::strerror(flushed ? errno : flush_errno) + ")";
  }
  return error_;
}

}  // namespace kiln
