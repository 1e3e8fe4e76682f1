// The files a glTF asset makes the loader read besides itself: buffer and image URIs that are not
// data URIs. Used to fingerprint an asset's inputs (batch resume) before it loads, so it applies
// the loader's own URI rule (gltf_uri_files.h) before any of those files is read. Knows the glTF
// and GLB layout only.
#pragma once

#include <string>
#include <vector>

#include "io/gltf/gltf_loader.h"

namespace kiln {

// Paths (the asset's canonical folder joined with each decoded URI) in the order the JSON lists
// them, each an existing regular file. Throws kiln::error as the loader would for the asset itself
// (missing, a FIFO, a device, a folder, too large; interrupted when options.cancel is raised) and
// for a URI the loader refuses (absolute, outside the folder unless
// options.allow_files_outside_folder, a FIFO or a device). Text that does not parse, JSON over
// options.limits.max_json_bytes, or JSON whose parse would pass options.memory's budget references
// nothing (and is not parsed): the loader reports what is wrong with it.
std::vector<std::string> gltf_referenced_files(const std::string& asset_path,
                                               const gltf_load_options& options);

}  // namespace kiln
