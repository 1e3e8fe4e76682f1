// Estimates of what loading a glTF file allocates, made before each allocation so that the job's
// memory budget (core/memory_budget.h) can refuse a file instead of running out of memory. They
// are rough upper bounds measured on kiln's own allocations and tinygltf's; internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

namespace kiln::gltf_internal {

// The JSON text's parse: the DOM kiln's pre-pass builds, then tinygltf's DOM and its model, which
// cost far more per byte for many small members than for long numbers and strings, so members
// (':') and values (',') are counted outside strings: measured ~520 bytes per one-member object
// and ~100 per number in an array, plus the text itself three times (copies and base64 buffers).
uint64_t json_parse_bytes(const uint8_t* text, size_t size);

// The sum of the buffers' declared byteLength in the JSON document: what tinygltf holds once it
// has read them (from files, data URIs or a GLB's BIN chunk).
uint64_t declared_buffer_bytes(const nlohmann::json& doc);

// One primitive's scene mesh and the temporary arrays its accessors are read into: every vertex
// attribute as floats, the indices, the triangle list and, for a normal-mapped material, tangents.
uint64_t primitive_bytes(const tinygltf::Model& model, const tinygltf::Primitive& prim);

// One decoded image (texels8 or texels32) and, while it decodes, kiln's buffer of it and the
// decoder's rows; width and height from its header, 16-bit PNGs from their IHDR.
struct image_bytes {
  uint64_t kept = 0;      // the scene's image
  uint64_t decoding = 0;  // freed once the image is decoded
};
image_bytes decoded_image_bytes(const uint8_t* data, size_t size, uint64_t width, uint64_t height);

}  // namespace kiln::gltf_internal
