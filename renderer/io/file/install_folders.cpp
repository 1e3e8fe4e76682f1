#include "io/file/install_folders.h"

#include <dlfcn.h>

#include <system_error>

namespace kiln {

namespace fs = std::filesystem;

install_folders find_install_folders() {
  install_folders folders;
  std::error_code ec;
  const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && executable.has_parent_path()) folders.executable = executable.parent_path();
  // The address of this function lies in whatever object kiln's code was linked into.
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&find_install_folders), &self) && self.dli_fname &&
      fs::path(self.dli_fname).is_absolute())
    folders.module = fs::path(self.dli_fname).parent_path();
  return folders;
}

}  // namespace kiln
