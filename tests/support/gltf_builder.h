// Builds small glTF 2.0 files for tests: meshes with one binary buffer embedded as a data URI,
// nodes, materials, punctual lights and cameras, written as .gltf JSON.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace kiln::testing {

class gltf_builder {
 public:
  gltf_builder();

  // Adds a mesh with one TRIANGLES primitive (TEXCOORD_0 when texcoords is not empty); returns the
  // mesh index.
  int add_mesh(const std::vector<std::array<float, 3>>& positions, const std::vector<uint32_t>& indices,
               int material = -1, const std::vector<std::array<float, 3>>& normals = {},
               const std::vector<std::array<float, 2>>& texcoords = {});

  // Adds a material; returns its index. Extra JSON (extensions) can be merged by the caller.
  int add_material(const nlohmann::json& material);

  // Adds a node; returns its index. The node is a root of scene 0 unless it becomes a child.
  int add_node(const nlohmann::json& node);
  void add_child(int parent, int child);

  // Adds a KHR_lights_punctual light; returns the light index (reference it from a node).
  int add_light(const nlohmann::json& light);

  // Adds a camera; returns its index.
  int add_camera(const nlohmann::json& camera);

  nlohmann::json& json() { return doc_; }

  // Finalises buffers and scene 0 and writes the file.
  void write(const std::string& path);

 private:
  int add_accessor(const void* data, size_t bytes, int component_type, const char* type, size_t count,
                   int target, const nlohmann::json& min = nullptr, const nlohmann::json& max = nullptr);

  nlohmann::json doc_;
  std::vector<uint8_t> buffer_;
  std::vector<bool> is_child_;
};

// base64 for data URIs.
std::string base64_encode(const std::vector<uint8_t>& bytes);

}  // namespace kiln::testing
