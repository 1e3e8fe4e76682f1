#include "app/text_output.h"

#include "io/exr/atomic_write.h"

namespace kiln {

void write_text_atomically(const std::string& path, const std::string& text) {
  // The writer the images use: a temporary name no other write shares, created by this call (never
  // a file or link placed at a guessable name), fsynced, renamed into place.
  write_atomically(path, "the file", [&](const temporary_file& temporary) {
    return write_all(temporary.fd, text.data(), text.size());
  });
}

}  // namespace kiln
