// KHR_draco_mesh_compression: decodes each compressed primitive's stream (draco_stream.h) into
// new buffers and bufferViews of the model and points the primitive's accessors at them, so
// that validation and accessor reading treat decoded data like any other. Runs after parsing,
// before gltf_validate. Internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>
#include <string>

namespace kiln {
class memory_charge;
}

namespace kiln::gltf_internal {

constexpr const char* draco_extension = "KHR_draco_mesh_compression";

// Before tinygltf parses the JSON: tinygltf refuses an index accessor without a bufferView,
// which a Draco primitive's may lack; such an accessor borrows the Draco stream's bufferView
// until decode_draco_primitives replaces it. True when `doc` changed. Throws kiln::error (input)
// when that extension names no existing bufferView.
bool lend_draco_index_views(nlohmann::json& doc, const std::string& file);

// Decodes every Draco primitive. A corrupt stream, a missing attribute id or a count that
// disagrees with the accessor throws kiln::error (input) naming the extension's JSON pointer.
// Decoded bytes are charged to `memory` (may be null).
void decode_draco_primitives(tinygltf::Model& model, const std::string& file, memory_charge* memory);

}  // namespace kiln::gltf_internal
