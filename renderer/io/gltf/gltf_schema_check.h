// What the glTF 2.0 schema requires of values tinygltf cannot be trusted to check, verified on
// the raw JSON before tinygltf parses it: tinygltf stores integers in int (2^32 names element 0,
// 2^32 + 1 element 1), reads -1, a fraction or a value of the wrong type as "absent", and reads an
// absent aspectRatio or zfar as 0, so none of these can be told apart once parsed. Each refusal
// names the JSON pointer of the value. Internal to io/gltf.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace kiln::gltf_internal {

// Throws input_error for the first integer property of the glTF schema or of an extension kiln
// reads (indices, byte offsets and lengths, counts, enums) that is not a JSON integer, lies below the
// schema's minimum or above what kiln stores, or, for an index, names no element of its collection.
void check_integer_properties(const nlohmann::json& doc, const std::string& path);

// Throws input_error for a camera's optional aspectRatio or perspective zfar that is given but
// not a number greater than 0 (zfar also greater than znear).
void check_camera_numbers(const nlohmann::json& doc, const std::string& path);

}  // namespace kiln::gltf_internal
