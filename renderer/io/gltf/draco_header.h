// The counts a Draco mesh stream's header declares, read without decoding it. libdraco sizes its
// connectivity arrays by them before checking them against the data that follows (fuzz_draco_stream:
// a few hundred bytes declaring 1.2 billion faces asked for 4.85 GB), so kiln reads them first and
// refuses a stream that declares more than its glTF accessors hold. Plain byte parsing, no libdraco:
// the layout is the Draco bitstream's (header "DRACO", major, minor, encoder type, method, flags; then
// for a sequential mesh its face and point counts, for an edgebreaker mesh its traversal type, new
// vertices before 2.2, encoded vertices and faces), uint32 before 2.0 (2.2 for sequential meshes),
// varints after. Internal to io/gltf.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

namespace kiln::gltf_internal {

struct draco_declared_counts {
  bool metadata = false;  // the header carries Draco metadata: the counts come after it, unread
  uint64_t faces = 0;
  uint64_t vertices = 0;  // points (sequential) or encoded vertices (edgebreaker): never more than the points
};

// The declared counts of a triangle-mesh stream, or nothing when the header is too short, is not a
// mesh's or uses an unknown method. A header with metadata (glTF never uses it; its length comes
// before the counts) comes back with `metadata` set and no counts.
std::optional<draco_declared_counts> read_draco_declared_counts(const uint8_t* data, size_t size);

}  // namespace kiln::gltf_internal
