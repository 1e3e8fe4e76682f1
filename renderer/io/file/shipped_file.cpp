#include "io/file/shipped_file.h"

#include <filesystem>

namespace kiln {

namespace fs = std::filesystem;

std::string shipped_file(const std::string& relative) {
  std::error_code ec;
  const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && executable.has_parent_path()) {
    const fs::path installed = executable.parent_path() / ".." / "share" / "kiln" / relative;
    if (fs::is_regular_file(installed, ec)) return installed.lexically_normal().string();
  }
  return (fs::path(KILN_SOURCE_SHARE) / relative).string();
}

}  // namespace kiln
