// Typed reading of glTF accessors: strided, sparse and normalised-integer data decoded into
// plain float or uint32 arrays. Reads assume gltf_validate has checked the accessor's layout
// against its bufferView and buffer; each read re-checks its byte range as an invariant.
// Internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// Bytes per component of a glTF 2.0 accessor componentType (5120..5126 without 5124); 0 otherwise.
size_t component_size(int component_type);

// Components per element of an accessor type (TINYGLTF_TYPE_*); 0 when unknown.
size_t component_count(int type);

// Bytes one element occupies, including the column padding glTF requires for MAT2/MAT3 of
// 1- and 2-byte components (each column starts on a 4-byte boundary); 0 when unknown.
size_t element_size(int component_type, int type);

// Names for messages: "UNSIGNED_SHORT", "VEC3".
std::string component_type_name(int component_type);
std::string type_name(int type);

// Reads accessor `index` as count*components floats. Normalised integers map to [0,1] or
// [-1,1] as the glTF specification defines; other integers convert to their value. An accessor
// without a bufferView reads as zeros before sparse substitution.
// Throws kiln::error (input) for sparse indices out of range or not increasing.
std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, const std::string& file);

// Reads a SCALAR UNSIGNED_BYTE/SHORT/INT accessor (indices) as uint32 values.
std::vector<uint32_t> read_accessor_indices(const tinygltf::Model& model, int index, const std::string& file);

}  // namespace kiln::gltf_internal
