// Placeholders that let tinygltf parse a file with compressed geometry: it refuses an index
// accessor without a bufferView (Draco) and a buffer without a uri outside a GLB (a meshopt
// fallback buffer). The placeholders are replaced by decoded data after parsing
// (gltf_draco.h, gltf_meshopt.h), before validation sees the model. Internal to io/gltf.
#pragma once

#include <nlohmann/json.hpp>

namespace kiln::gltf_internal {

// Adds every placeholder the document needs; true when it changed.
bool add_compression_placeholders(nlohmann::json& doc);

}  // namespace kiln::gltf_internal
