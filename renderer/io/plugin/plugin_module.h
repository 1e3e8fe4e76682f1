// Finding and opening kiln's plugin modules (the image codecs, the colour module): shared objects
// that hold a heavy dependency, opened with dlopen the first time a render needs them so that a
// process which never does pays nothing for it. Depends on core and libdl only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"

namespace kiln {

// Where a module is looked for and how it is entered. Its entry symbol returns a table whose
// first two fields are the uint32_t abi and table_bytes both sides were built with.
struct plugin_search {
  std::string file_name;     // "kiln_image_codecs.so", the same in the build tree and after install
  std::string env_variable;  // when set, the only place looked at ("KILN_IMAGE_CODECS")
  std::string build_path;    // the build tree's copy, looked at last; empty: none
  std::string entry_symbol;  // the exported function returning the table
  uint32_t abi = 0;          // the table version this kiln needs
  uint32_t table_bytes = 0;  // sizeof the table here: a second check of the layout
};

// The places looked at, in order: $env_variable alone when set; else beside the running
// executable, in ../lib/kiln/ beside it (an install), beside the shared object this code is part
// of and in its lib/kiln/ (the Python package carries the modules there), and build_path.
std::vector<std::string> plugin_candidates(const plugin_search& search);

// An opened module's table, or why none could be opened (then table is null).
struct opened_plugin {
  const void* table = nullptr;
  std::string failure;  // "<path>: <why>" or "not found (looked for ...)"
};

// Opens the first candidate that exists (one that exists but does not open is reported, not passed
// over, so a broken install is not hidden by a stale copy) and checks its table's version. The
// module is never closed: its libraries keep threads and static state until the process exits.
opened_plugin open_plugin(const plugin_search& search);

// The table of the module search finds, opened on the first call (thread-safe; one static per table
// type, so per module). Throws kiln::error (io) with one line, "<needs> the <what>: <failure>",
// when it cannot be opened.
template <typename Table>
const Table& plugin_table(const plugin_search& search, const std::string& needs, const std::string& what) {
  static const opened_plugin module = open_plugin(search);
  if (!module.table) throw error(error_kind::io, "", "", needs + " the " + what + ": " + module.failure);
  return *static_cast<const Table*>(module.table);
}

}  // namespace kiln
