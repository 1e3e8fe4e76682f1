#include "io/gltf/gltf_memory.h"

#include <algorithm>

namespace kiln::gltf_internal {

namespace {

// Measured with /usr/bin/time -v on padded files (tools/make_memory_cases.py): 10 MB of
// {"k":1} objects peak at 781 MB, 1.5 million members; arrays of numbers at ~100 bytes a value.
constexpr uint64_t bytes_per_member = 520;
constexpr uint64_t bytes_per_value = 100;
constexpr uint64_t text_copies = 3;

size_t accessor_count(const tinygltf::Model& model, int accessor) {
  if (accessor < 0 || size_t(accessor) >= model.accessors.size()) return 0;
  return model.accessors[size_t(accessor)].count;
}

}  // namespace

uint64_t json_parse_bytes(const uint8_t* text, size_t size) {
  uint64_t members = 0, values = 1;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const uint8_t c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == ':') {
      ++members;
    } else if (c == ',') {
      ++values;
    }
  }
  return text_copies * uint64_t(size) + members * bytes_per_member + values * bytes_per_value;
}

uint64_t declared_buffer_bytes(const nlohmann::json& doc) {
  uint64_t total = 0;
  auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return 0;
  for (const auto& buffer : *buffers) {
    if (!buffer.is_object()) continue;
    auto length = buffer.find("byteLength");
    if (length != buffer.end() && length->is_number_unsigned()) total += length->get<uint64_t>();
  }
  return total;
}

uint64_t primitive_bytes(const tinygltf::Model& model, const tinygltf::Primitive& prim) {
  auto position = prim.attributes.find("POSITION");
  const uint64_t vertices = position == prim.attributes.end() ? 0 : accessor_count(model, position->second);
  // A strip or fan of n indices makes up to 3n triangle-list indices.
  const uint64_t indices = prim.indices >= 0 ? accessor_count(model, prim.indices) : vertices;
  // Per vertex: every attribute the scene may keep (position, normal, two UV sets, tangent,
  // colour: 12 + 12 + 8 + 8 + 16 + 16) and the float array one is read into (at most 16).
  const uint64_t per_vertex = 72 + 16;
  // Per index: the indices read, the triangle list and the mesh's own (4 bytes each, up to 3x).
  const uint64_t per_index = 4 + 12 + 12;
  return vertices * per_vertex + indices * per_index;
}

image_bytes decoded_image_bytes(const uint8_t* data, size_t size, uint64_t width, uint64_t height) {
  // PNG's IHDR: bit depth at byte 24. Deeper images decode to float RGBA (16 bytes a texel).
  const bool deep = size > 24 && data[0] == 0x89 && data[1] == 'P' && data[24] == 16;
  const uint64_t texels = width * height;
  image_bytes b;
  b.kept = texels * (deep ? 16 : 4);
  // While decoding: kiln's buffer of the file's channels (up to 4, as float for deep images) and
  // the decoder's rows (measured: a 16384² RGB PNG peaks 0.75 GiB over its kept 1 GiB).
  b.decoding = texels * (deep ? 16 + 2 : 4 + 1);
  return b;
}

}  // namespace kiln::gltf_internal
