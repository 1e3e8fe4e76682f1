// Writes small text outputs (JSON and CSV reports) the way kiln writes images: to a temporary file
// beside the target, renamed into place only when complete, so a failure never leaves half a report.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace kiln {

// Throws kiln::error (io) naming the path when the text cannot be written (io/exr/atomic_write.h).
void write_text_atomically(const std::string& path, const std::string& text);

// Writes object with object[list_key] = [item(0), ..., item(count - 1)] as dump(2) would (bytes
// that are not UTF-8 replaced), atomically, but one item at a time: a plan or summary of a million
// jobs never holds the whole document. item may throw; then nothing is written.
void write_json_list_atomically(const std::string& path, const nlohmann::json& object,
                                const std::string& list_key, size_t count,
                                const std::function<nlohmann::json(size_t)>& item);

}  // namespace kiln
