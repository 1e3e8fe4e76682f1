// Where this copy of kiln runs from: the running executable's folder and the folder of the shared
// object holding kiln's code (the Python module's, inside its package). Plugin modules
// (io/plugin) and shipped files (shipped_file.h) are looked for from these. Depends on nothing but
// the standard library and libdl.
#pragma once

#include <filesystem>
#include <optional>

namespace kiln {

struct install_folders {
  std::optional<std::filesystem::path> executable;  // /proc/self/exe's folder
  // The shared object's folder when kiln is linked into one (for an executable: its own folder).
  std::optional<std::filesystem::path> module;
};

install_folders find_install_folders();

}  // namespace kiln
