// The files a glTF asset makes the loader read besides itself: buffer and image URIs that are not
// data URIs. Used to fingerprint an asset's inputs (batch resume), not to load it. Knows the
// glTF and GLB layout only; depends on the standard library.
#pragma once

#include <string>
#include <vector>

namespace kiln {

// Paths (the asset's folder joined with each percent-decoded URI) in the order the JSON lists
// them. Never throws: a file that cannot be read or parsed references nothing, so the loader is
// the one that reports what is wrong with it.
std::vector<std::string> gltf_referenced_files(const std::string& asset_path);

}  // namespace kiln
