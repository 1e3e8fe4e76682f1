#include "io/plugin/plugin_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "io/file/install_folders.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// dlerror() usually starts with the path already; the message names it once.
std::string naming_path(const std::string& path, const char* why) {
  const std::string text = why ? why : "unknown error";
  return text.compare(0, path.size(), path) == 0 ? text : path + ": " + text;
}

const char* forced_path(const plugin_search& search) {
  const char* forced = std::getenv(search.env_variable.c_str());
  return forced && *forced ? forced : nullptr;
}

// The two fields every module table starts with.
struct table_head {
  uint32_t abi;
  uint32_t table_bytes;
};

}  // namespace

std::vector<std::string> plugin_candidates(const plugin_search& search) {
  if (const char* forced = forced_path(search)) return {forced};
  std::vector<std::string> candidates;
  const auto add = [&](const fs::path& path) {
    const std::string text = path.lexically_normal().string();
    for (const std::string& known : candidates)
      if (known == text) return;
    candidates.push_back(text);
  };
  const install_folders folders = find_install_folders();
  if (folders.executable) {
    add(*folders.executable / search.file_name);
    add(*folders.executable / ".." / "lib" / "kiln" / search.file_name);
  }
  // For the kiln executable this is its folder again; for the Python module, the module's own
  // and the package's lib/kiln (the package is laid out as an install prefix).
  if (folders.module) {
    add(*folders.module / search.file_name);
    add(*folders.module / "lib" / "kiln" / search.file_name);
  }
  if (!search.build_path.empty()) add(search.build_path);
  return candidates;
}

opened_plugin open_plugin(const plugin_search& search) {
  const bool only_forced = forced_path(search) != nullptr;
  const std::vector<std::string> candidates = plugin_candidates(search);
  for (const std::string& path : candidates) {
    std::error_code ec;
    if (!only_forced && !fs::is_regular_file(path, ec)) continue;
    // RTLD_LOCAL: the dependency's symbols stay private to the module.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) return {nullptr, naming_path(path, ::dlerror())};
    using entry_function = const void* (*)();
    auto entry = reinterpret_cast<entry_function>(::dlsym(handle, search.entry_symbol.c_str()));
    if (!entry) return {nullptr, naming_path(path, ::dlerror())};
    const void* table = entry();
    table_head head{0, 0};
    if (table) std::memcpy(&head, table, sizeof head);
    if (!table || head.abi != search.abi || head.table_bytes != search.table_bytes)
      return {nullptr, path + ": built for another kiln (table version " + std::to_string(head.abi) +
                           ", this kiln needs " + std::to_string(search.abi) + ")"};
    return {table, ""};
  }
  std::string looked;
  for (const std::string& path : candidates) looked += (looked.empty() ? "" : ", ") + path;
  return {nullptr, "not found (looked for " + looked + ")"};
}

}  // namespace kiln
