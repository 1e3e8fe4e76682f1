#include "io/file/shipped_file.h"

#include <filesystem>

#include "io/file/install_folders.h"

namespace kiln {

namespace fs = std::filesystem;

std::string shipped_file(const std::string& relative) {
  // An install prefix's share/kiln: beside bin/ for the executable, inside the Python package
  // (kiln/share/kiln) for the module.
  const install_folders folders = find_install_folders();
  std::error_code ec;
  if (folders.executable) {
    const fs::path installed = *folders.executable / ".." / "share" / "kiln" / relative;
    if (fs::is_regular_file(installed, ec)) return installed.lexically_normal().string();
  }
  if (folders.module) {
    const fs::path packaged = *folders.module / "share" / "kiln" / relative;
    if (fs::is_regular_file(packaged, ec)) return packaged.lexically_normal().string();
  }
  return (fs::path(KILN_SOURCE_SHARE) / relative).string();
}

}  // namespace kiln
