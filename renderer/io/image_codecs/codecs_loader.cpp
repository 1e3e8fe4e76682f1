#include "io/image_codecs/codecs_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// The module, or why it could not be opened (then table is null).
struct opened_module {
  const image_codecs* table = nullptr;
  std::string failure;
};

// dlerror() usually starts with the path already; the message names it once.
std::string naming_path(const std::string& path, const char* why) {
  const std::string text = why ? why : "unknown error";
  return text.compare(0, path.size(), path) == 0 ? text : path + ": " + text;
}

opened_module open_module() {
  const char* forced = std::getenv("KILN_IMAGE_CODECS");
  const bool only_forced = forced && *forced;
  const std::vector<std::string> candidates = image_codecs_candidates();
  for (const std::string& path : candidates) {
    std::error_code ec;
    // Without the variable the first file that exists is the module; one that exists but does not
    // open is reported rather than passed over, so a broken install is not hidden by a stale copy.
    if (!only_forced && !fs::is_regular_file(path, ec)) continue;
    // RTLD_LOCAL: OpenImageIO's symbols stay private to the module. It is never closed: its
    // libraries keep threads and static state until the process exits.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) return {nullptr, naming_path(path, ::dlerror())};
    using entry_function = const image_codecs* (*)();
    auto entry = reinterpret_cast<entry_function>(::dlsym(handle, KILN_IMAGE_CODECS_ENTRY));
    if (!entry) return {nullptr, naming_path(path, ::dlerror())};
    const image_codecs* table = entry();
    if (!table || table->abi != image_codecs_abi || table->table_bytes != sizeof(image_codecs))
      return {nullptr, path + ": built for another kiln (table version " +
                           std::to_string(table ? table->abi : 0) + ", this kiln needs " +
                           std::to_string(image_codecs_abi) + ")"};
    return {table, ""};
  }
  std::string looked;
  for (const std::string& path : candidates) looked += (looked.empty() ? "" : ", ") + path;
  return {nullptr, "not found (looked for " + looked + ")"};
}

}  // namespace

std::vector<std::string> image_codecs_candidates() {
  if (const char* forced = std::getenv("KILN_IMAGE_CODECS"); forced && *forced) return {forced};
  std::vector<std::string> candidates;
  const auto add = [&](const fs::path& path) {
    const std::string text = path.lexically_normal().string();
    for (const std::string& known : candidates)
      if (known == text) return;
    candidates.push_back(text);
  };
  std::error_code ec;
  const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && executable.has_parent_path()) {
    add(executable.parent_path() / image_codecs_file_name);
    add(executable.parent_path() / ".." / "lib" / "kiln" / image_codecs_file_name);
  }
  // Beside the shared object this loader is part of: the Python module installs the codecs module
  // next to itself (for the kiln executable this is the executable's folder again).
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&image_codecs_candidates), &self) && self.dli_fname &&
      fs::path(self.dli_fname).is_absolute())
    add(fs::path(self.dli_fname).parent_path() / image_codecs_file_name);
#ifdef KILN_IMAGE_CODECS_BUILD_PATH
  // Tests and tools built in other folders of the build tree find the module where it was built.
  add(KILN_IMAGE_CODECS_BUILD_PATH);
#endif
  return candidates;
}

const image_codecs& load_image_codecs(const std::string& needs) {
  static const opened_module module = open_module();  // thread-safe, once per process
  if (!module.table)
    throw error(error_kind::io, "", "", needs + " the image codecs module: " + module.failure);
  return *module.table;
}

}  // namespace kiln
