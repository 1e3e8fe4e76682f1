// Placeholders that let tinygltf parse a file with compressed geometry: it refuses an index
// accessor without a bufferView (Draco) and a buffer without a uri outside a GLB (a meshopt
// fallback buffer). The placeholders are replaced by decoded data after parsing
// (gltf_draco.h, gltf_meshopt.h), before validation sees the model. Internal to io/gltf.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace kiln::gltf_internal {

// Adds every placeholder the document needs; true when it changed. Throws kiln::error (input),
// naming `file` and the JSON pointer, for a compressed primitive that names no data.
bool add_compression_placeholders(nlohmann::json& doc, const std::string& file);

}  // namespace kiln::gltf_internal
