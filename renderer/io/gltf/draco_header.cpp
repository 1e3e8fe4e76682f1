#include "io/gltf/draco_header.h"

#include <cstring>

namespace kiln::gltf_internal {

namespace {

// Reads values from the stream in order; any read past the end marks it failed.
struct reader {
  const uint8_t* data;
  size_t size;
  size_t at = 0;
  bool failed = false;

  uint64_t byte() {
    if (at >= size) {
      failed = true;
      return 0;
    }
    return data[at++];
  }
  uint64_t u16() { return byte() | byte() << 8; }
  uint64_t u32() { return byte() | byte() << 8 | byte() << 16 | byte() << 24; }
  // Draco's unsigned LEB128 (at most 5 bytes for 32 bits; a longer one is corrupt).
  uint64_t varint() {
    uint64_t value = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      const uint64_t b = byte();
      value |= (b & 0x7f) << shift;
      if ((b & 0x80) == 0) return value;
    }
    failed = true;
    return 0;
  }
};

constexpr uint64_t version(uint64_t major, uint64_t minor) { return major << 8 | minor; }
constexpr int mesh_encoder = 1, sequential = 0, edgebreaker = 1;
constexpr uint64_t metadata_flag = 0x8000;

}  // namespace

std::optional<draco_declared_counts> read_draco_declared_counts(const uint8_t* data, size_t size) {
  if (size < 11 || std::memcmp(data, "DRACO", 5) != 0) return std::nullopt;
  reader in{data, size, 5};
  const uint64_t major = in.byte(), minor = in.byte();
  const uint64_t encoder = in.byte(), method = in.byte(), flags = in.u16();
  const uint64_t v = version(major, minor);
  if (encoder != mesh_encoder) return std::nullopt;
  draco_declared_counts counts;
  if (v >= version(1, 3) && (flags & metadata_flag)) {
    counts.metadata = true;
    return counts;
  }
  if (method == sequential) {
    const bool fixed = v < version(2, 2);
    counts.faces = fixed ? in.u32() : in.varint();
    counts.vertices = fixed ? in.u32() : in.varint();
  } else if (method == edgebreaker) {
    in.byte();  // the traversal decoder's type
    const bool fixed = v < version(2, 0);
    if (v < version(2, 2)) fixed ? in.u32() : in.varint();  // new vertices, unused here
    counts.vertices = fixed ? in.u32() : in.varint();
    counts.faces = fixed ? in.u32() : in.varint();
  } else {
    return std::nullopt;
  }
  if (in.failed) return std::nullopt;
  return counts;
}

}  // namespace kiln::gltf_internal
