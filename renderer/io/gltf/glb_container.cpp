#include "io/gltf/glb_container.h"

#include <cstdio>

#include "core/error.h"

namespace kiln::gltf_internal {
namespace {

constexpr uint32_t magic_gltf = 0x46546C67;  // "glTF" read as little-endian uint32
constexpr uint32_t chunk_json = 0x4E4F534A;  // "JSON"
constexpr uint32_t chunk_bin = 0x004E4942;   // "BIN\0"
constexpr size_t header_bytes = 12;
constexpr size_t chunk_header_bytes = 8;

// GLB integers are little-endian whatever the host is.
uint32_t read_u32_le(const std::vector<uint8_t>& bytes, size_t offset) {
  return static_cast<uint32_t>(bytes[offset]) | (static_cast<uint32_t>(bytes[offset + 1]) << 8) |
         (static_cast<uint32_t>(bytes[offset + 2]) << 16) | (static_cast<uint32_t>(bytes[offset + 3]) << 24);
}

std::string hex(uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", v);
  return text;
}

}  // namespace

bool has_glb_magic(const std::vector<uint8_t>& bytes) {
  return bytes.size() >= 4 && read_u32_le(bytes, 0) == magic_gltf;
}

glb_layout check_glb_container(const std::vector<uint8_t>& bytes, const std::string& file) {
  auto fail = [&](const std::string& reason) { return input_error(file, "", "GLB: " + reason); };

  if (bytes.size() < header_bytes)
    throw fail("file is " + std::to_string(bytes.size()) + " bytes, shorter than the 12-byte GLB header");
  if (read_u32_le(bytes, 0) != magic_gltf)
    throw fail("bad magic " + hex(read_u32_le(bytes, 0)) + " (expected \"glTF\")");
  const uint32_t version = read_u32_le(bytes, 4);
  if (version != 2) throw fail("unsupported container version " + std::to_string(version) + " (expected 2)");
  const uint64_t declared = read_u32_le(bytes, 8);
  if (declared != bytes.size())
    throw fail("header declares " + std::to_string(declared) + " bytes but the file has " +
               std::to_string(bytes.size()));

  glb_layout layout;
  bool seen_json = false;
  size_t chunk_index = 0;
  size_t offset = header_bytes;
  // Each step consumes at least the 8-byte chunk header, so the loop ends within size/8 steps.
  while (offset < bytes.size()) {
    const std::string which = "chunk " + std::to_string(chunk_index);
    if (bytes.size() - offset < chunk_header_bytes)
      throw fail(which + " header is truncated (" + std::to_string(bytes.size() - offset) +
                 " bytes left, 8 needed)");
    const uint64_t length = read_u32_le(bytes, offset);
    const uint32_t type = read_u32_le(bytes, offset + 4);
    const size_t data_offset = offset + chunk_header_bytes;
    if (length % 4 != 0) throw fail(which + " length " + std::to_string(length) + " is not a multiple of 4");
    if (length > bytes.size() - data_offset)
      throw fail(which + " needs " + std::to_string(length) + " bytes but only " +
                 std::to_string(bytes.size() - data_offset) + " remain in the file");

    if (chunk_index == 0) {
      if (type != chunk_json) throw fail("first chunk has type " + hex(type) + ", expected JSON");
      if (length == 0) throw fail("JSON chunk is empty");
      layout.json_offset = data_offset;
      layout.json_length = static_cast<size_t>(length);
      seen_json = true;
    } else if (type == chunk_json) {
      throw fail(which + " is a second JSON chunk");
    } else if (type == chunk_bin) {
      if (layout.has_bin) throw fail(which + " is a second BIN chunk");
      if (chunk_index != 1) throw fail(which + " is a BIN chunk; BIN must be the second chunk");
      layout.has_bin = true;
      layout.bin_offset = data_offset;
      layout.bin_length = static_cast<size_t>(length);
    }
    // Chunks of other types are ignored, as the GLB specification requires.
    offset = data_offset + static_cast<size_t>(length);
    ++chunk_index;
  }
  if (!seen_json) throw fail("no JSON chunk");
  return layout;
}

namespace {
void append_u32_le(std::vector<uint8_t>& out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
}
}  // namespace

std::vector<uint8_t> glb_with_json(const std::vector<uint8_t>& bytes, const glb_layout& layout,
                                   const std::string& json) {
  std::string text = json;
  while (text.size() % 4 != 0) text += ' ';
  std::vector<uint8_t> out;
  append_u32_le(out, magic_gltf);
  append_u32_le(out, 2);
  append_u32_le(out, 0);  // total length, set below
  append_u32_le(out, static_cast<uint32_t>(text.size()));
  append_u32_le(out, chunk_json);
  out.insert(out.end(), text.begin(), text.end());
  if (layout.has_bin) {
    append_u32_le(out, static_cast<uint32_t>(layout.bin_length));
    append_u32_le(out, chunk_bin);
    out.insert(out.end(), bytes.begin() + static_cast<std::ptrdiff_t>(layout.bin_offset),
               bytes.begin() + static_cast<std::ptrdiff_t>(layout.bin_offset + layout.bin_length));
  }
  const uint32_t total = static_cast<uint32_t>(out.size());
  for (int k = 0; k < 4; ++k) out[8 + k] = static_cast<uint8_t>(total >> (8 * k));
  return out;
}

}  // namespace kiln::gltf_internal
