// Writes small text outputs (JSON and CSV reports) the way kiln writes images: to a temporary file
// beside the target, renamed into place only when complete, so a failure never leaves half a report.
#pragma once

#include <string>

namespace kiln {

// Throws kiln::error (io) naming the path when the text cannot be written (io/exr/atomic_write.h).
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace kiln
