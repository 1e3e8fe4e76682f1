// Decoding of one KHR_draco_mesh_compression stream through Debian's libdraco into plain arrays:
// glTF-typed attribute bytes and uint32 triangle indices. Knows no glTF JSON (gltf_draco.h maps
// accessors to requests), so the fuzz target can drive it with bytes alone. Internal to io/gltf.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// One attribute wanted from the stream: its Draco unique id, and the glTF componentType
// (5120..5126 without 5124) and component count its accessor declares.
struct draco_attribute_want {
  uint32_t id = 0;
  int component_type = 0;
  size_t components = 0;
};

// A decoded stream. Attributes follow the order of the wants; each holds point_count elements
// tightly packed, little-endian, quantisation already undone by the decoder.
struct draco_geometry {
  uint32_t point_count = 0;
  bool is_mesh = false;           // always a triangle mesh: point clouds are refused
  std::vector<uint32_t> indices;  // three per triangle, each below point_count
  std::vector<std::vector<uint8_t>> attributes;
};

// What the stream's accessors hold: a stream whose header declares more faces or vertices is
// refused before libdraco allocates by those counts (draco_header.h).
struct draco_stream_limits {
  uint64_t max_faces = UINT64_MAX;
  uint64_t max_points = UINT64_MAX;
};

// Decodes `size` bytes. A corrupt or truncated stream, a point cloud (kiln renders triangles
// only), a header declaring more than `limits`, a missing attribute id, or an attribute whose
// component count differs from the want returns nothing and says why in `problem`.
std::optional<draco_geometry> decode_draco_stream(const uint8_t* data, size_t size,
                                                  const std::vector<draco_attribute_want>& wants,
                                                  const draco_stream_limits& limits, std::string& problem);

}  // namespace kiln::gltf_internal
