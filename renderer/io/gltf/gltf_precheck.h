// Checks on the raw JSON of what tinygltf would refuse in its own words, without a JSON path
// ("File not found : x", "number overflow parsing '1e309'", "accessor[1] invalid bufferView"):
// run before tinygltf parses, each refusal names the JSON pointer of the value at fault.
// Internal to io/gltf.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// Where the buffers of a file can come from.
struct buffer_sources {
  std::string folder_prefix;  // canonical asset folder, ending in '/': relative URIs resolve here
  bool is_glb = false;
  bool has_bin = false;   // GLB: the file has a BIN chunk
  size_t bin_length = 0;  // GLB: its length in bytes
  // An asset in memory: the files its URIs name, instead of the folder's (gltf_loader.h).
  const std::map<std::string, std::vector<uint8_t>>* memory_files = nullptr;
};

// Throws input_error when text is not JSON, naming the pointer of the value where parsing
// stopped (a number too large for a double, such as 1e309, is refused there too) and the line
// and column. Returns normally when the text parses.
void check_json_syntax(const uint8_t* text, size_t size, const std::string& path);

// Throws input_error for the first buffer, bufferView, image, primitive or light that tinygltf
// would refuse: buffers without a source, malformed data URIs, byteLength that disagrees with the
// data, missing buffer files, invalid byteStride, dangling image bufferViews and index accessors,
// spot lights without their "spot" object. URIs have already passed the folder policy.
void check_what_tinygltf_refuses(const nlohmann::json& doc, const std::string& path,
                                 const buffer_sources& sources);

}  // namespace kiln::gltf_internal
