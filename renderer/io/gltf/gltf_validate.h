// Structural validation of a parsed glTF model, done before any buffer byte is read: every
// index reference in range, every bufferView inside its buffer, every accessor inside its
// bufferView (overflow-safe 64-bit arithmetic), mesh attribute formats, a node graph that is a
// forest (no cycles, one parent per node), finite node transforms, sane cameras and lights.
// Internal to io/gltf. Data-dependent checks (index values, NaN positions) happen while reading.
#pragma once

#include <tiny_gltf.h>

#include <string>

namespace kiln::gltf_internal {

constexpr const char* quantization_extension = "KHR_mesh_quantization";

// Throws kiln::error (input) with the file, the JSON pointer of the first problem and a reason.
void validate_model(const tinygltf::Model& model, const std::string& file);

// True when the file lists `name` in extensionsUsed.
bool uses_extension(const tinygltf::Model& model, const std::string& name);

// The KHR_lights_punctual light a node places, or -1. Only meaningful after validate_model,
// which guarantees the index is in range.
int node_light_index(const tinygltf::Node& node);

}  // namespace kiln::gltf_internal
