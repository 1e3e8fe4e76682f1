// An OpenEXR output stream on a file that remembers its first failure. OpenEXR writes a part's
// offset table from a destructor that swallows every exception, so without this a full disk at
// that moment would leave a broken file that looks written. Inside io/exr only.
#pragma once

#include <OpenEXR/ImfIO.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace kiln {

class exr_file_stream final : public Imf::OStream {
 public:
  // Writes through a duplicate of fd, a file made for the write (io/exr/atomic_write.h), from its
  // current offset; fd itself stays open. path names the file in OpenEXR's messages. error() says
  // why when fd cannot be used.
  exr_file_stream(int fd, const std::string& path);
  ~exr_file_stream() override;
  exr_file_stream(const exr_file_stream&) = delete;
  exr_file_stream& operator=(const exr_file_stream&) = delete;

  // Imf::OStream: each throws Iex::IoExc on failure, after recording it.
  void write(const char c[], int n) override;
  uint64_t tellp() override;
  void seekp(uint64_t pos) override;

  // Flushes and closes the file; returns "" or the first failure of any open, write, seek or the
  // close itself.
  std::string close();

  // The first failure so far, "" when none.
  const std::string& error() const { return error_; }

 private:
  [[noreturn]] void fail(const char* what);

  std::FILE* file_ = nullptr;
  std::string error_;
};

}  // namespace kiln
