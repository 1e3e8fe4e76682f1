// Reading a file that a scene or a command line names, without trusting what the path is: it may
// name a FIFO (opening one waits for a writer, forever), a device (/dev/zero never ends), a folder
// or a file larger than kiln reads. Such paths are refused before a byte is read, reads stop as
// soon as a cancel flag is raised, and a file is read only up to the size it had when opened.
// Depends on core only; knows no file format.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace kiln {

// How to read one input file and how errors name it.
struct input_file_request {
  uint64_t max_bytes = 0;                     // a larger file is refused
  const std::atomic<bool>* cancel = nullptr;  // when set and raised, reading stops (checked per chunk)
  std::string file;                           // the file errors name (default: the path itself)
  std::string where;                          // the place in it, e.g. /buffers/0/uri or --environment

  // So that {limit} and {limit, &flag} read as what they are.
  input_file_request(uint64_t max, const std::atomic<bool>* stop = nullptr, std::string named = "",
                     std::string place = "")
      : max_bytes(max), cancel(stop), file(std::move(named)), where(std::move(place)) {}
};

// Why path cannot be read as an input (it names a FIFO, a device, a folder, or a file over
// max_bytes), or "" when it is a regular file within the limit or does not exist. Follows
// symbolic links, so a link to /dev/zero is a character device. Opens nothing.
std::string input_file_problem(const std::string& path, uint64_t max_bytes);

// True when path names nothing (ENOENT or ENOTDIR).
bool input_file_missing(const std::string& path);

// Hands successive chunks of the regular file at path to consume. The file is checked with
// stat() before it is opened (opening some devices has effects), opened with O_NONBLOCK and
// checked again with fstat() (the path may have changed in between), and read up to the size
// fstat() gave. Throws kiln::error: input (exit 2) for a path that is missing or not a regular
// file within request.max_bytes, naming request.file and request.where; io for a read failure;
// interrupted as soon as *request.cancel is true.
void read_input_file(const std::string& path, const input_file_request& request,
                     const std::function<void(const char* bytes, size_t count)>& consume);

// The whole file, read as read_input_file does.
std::vector<uint8_t> read_whole_input_file(const std::string& path, const input_file_request& request);

}  // namespace kiln
