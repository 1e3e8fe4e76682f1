// The asset argument of every subcommand must name a regular file: a folder makes the stream
// library fail with no file name, and a FIFO or device would block or never end. Checked with
// stat(2) before any byte is read.
#pragma once

#include <string>

namespace kiln {

// Throws kiln::error (input) naming path (and where, e.g. a manifest's "FILE: /jobs/3") when it
// holds a NUL or exists and is not a regular file; a missing path is left to the loader, which
// names it.
void check_asset_file(const std::string& path, const std::string& where = "");

// Throws kiln::error (input) at where when path holds a NUL character. The system reads a path
// up to its first NUL, so "a.gltf\0b" would open a.gltf; only Python and JSON can pass one.
void check_no_nul(const std::string& path, const std::string& where);

}  // namespace kiln
