// EXT_meshopt_compression: decodes each compressed bufferView (meshoptimizer's vertex and index
// codecs, then its OCTAHEDRAL, QUATERNION or EXPONENTIAL filter) into a new buffer and points
// the bufferView at it, so that accessors over it validate and read like any other. Runs
// after parsing, before Draco and gltf_validate. Internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>
#include <string>

namespace kiln {
class memory_charge;
}

namespace kiln::gltf_internal {

constexpr const char* meshopt_extension = "EXT_meshopt_compression";

// Before tinygltf parses the JSON: a fallback buffer (the extension's "fallback": true) may have
// no uri, which tinygltf refuses outside a GLB (and inside one reads the BIN chunk into it);
// such a buffer gets a 4-byte data URI, emptied again after parsing. True when `doc` changed.
bool fill_meshopt_fallback_buffers(nlohmann::json& doc);

// Decodes every compressed bufferView. A malformed extension object, a stream the decoder
// refuses, or a plain bufferView reading a fallback buffer throws kiln::error (input) naming
// the JSON pointer. Decoded bytes are charged to `memory` (may be null).
void decode_meshopt_views(tinygltf::Model& model, const std::string& file, memory_charge* memory);

}  // namespace kiln::gltf_internal
