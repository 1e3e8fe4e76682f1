// The KILN_quadric extension: analytic primitives in glTF (schema in docs/quadrics.md).
// Definitions live once at the root (extensions.KILN_quadric.primitives); nodes place them with
// extensions.KILN_quadric {primitive, material}. Internal to io/gltf; every bad value throws
// kiln::error (input) naming the JSON path, e.g. /nodes/3/extensions/KILN_quadric/primitive.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace kiln::gltf_internal {

constexpr const char* quadric_extension = "KILN_quadric";

// Reads and checks every definition in the root extension, in file order (scene.quadrics).
std::vector<quadric> read_quadric_definitions(const tinygltf::Model& model, const std::string& file);

// What a node's KILN_quadric places: a definition index and a glTF material (-1: default).
struct quadric_placement {
  uint32_t primitive = 0;
  int material = -1;
};

// The node's placement, or empty when the node has no KILN_quadric extension.
std::optional<quadric_placement> read_quadric_placement(const tinygltf::Model& model, int node_index,
                                                        size_t definition_count, const std::string& file);

}  // namespace kiln::gltf_internal
