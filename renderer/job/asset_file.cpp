#include "job/asset_file.h"

#include <sys/stat.h>

#include "core/error.h"
#include "core/message_text.h"

namespace kiln {

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

void check_no_nul(const std::string& path, const std::string& where) {
  if (path.find('\0') != std::string::npos)
    throw input_error("", where, quoted(path) + " holds a NUL character, which no file name can");
}

void check_asset_file(const std::string& path, const std::string& where) {
  check_no_nul(path, where.empty() ? "asset" : where);
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0 || S_ISREG(s.st_mode)) return;
  const std::string reason = std::string(kind_of(s.st_mode)) + ", not a glTF file (.gltf or .glb)";
  if (where.empty()) throw input_error(path, "", reason);
  throw input_error("", where, path + " is " + reason);
}

}  // namespace kiln
