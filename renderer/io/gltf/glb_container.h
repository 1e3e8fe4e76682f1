// Our own check of a binary glTF (.glb) container, done before tinygltf sees the bytes:
// tinygltf 2.7's own checks miss some truncations (its BIN chunk bound ignores the chunk
// header). Internal to io/gltf; depends on core/error only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// Where the chunks of a well-formed GLB lie inside the file bytes.
struct glb_layout {
  size_t json_offset = 0;  // first byte of the JSON chunk's data
  size_t json_length = 0;
  bool has_bin = false;
  size_t bin_offset = 0;  // first byte of the BIN chunk's data
  size_t bin_length = 0;
};

// Checks the 12-byte header (magic "glTF", version 2, declared length == file size) and every
// chunk (complete 8-byte header, 4-byte aligned length that fits in the file, JSON first and
// once, BIN only second and once, unknown chunk types skipped as the spec asks).
// Throws kiln::error (input) naming `file` on any violation.
glb_layout check_glb_container(const std::vector<uint8_t>& bytes, const std::string& file);

// The same container with its JSON chunk's text replaced by `json` (padded with spaces to a
// multiple of 4 bytes, as the spec asks) and its BIN chunk, if any, kept as it was.
std::vector<uint8_t> glb_with_json(const std::vector<uint8_t>& bytes, const glb_layout& layout,
                                   const std::string& json);

// True when the bytes start with the GLB magic "glTF".
bool has_glb_magic(const std::vector<uint8_t>& bytes);

}  // namespace kiln::gltf_internal
