// Builds small glTF 2.0 files for tests: one binary buffer whose bytes collect in `bin`, meshes,
// nodes, materials, punctual lights and cameras, written as .gltf (the buffer as a data URI or an
// external .bin) or as .glb. The document is public so that a test can break it on purpose.
// Used by the loader's unit tests and the end-to-end tests alike; depends on nlohmann::json only.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace kiln::testing {

struct gltf_builder {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}, {"generator", "kiln tests"}}}};
  std::vector<uint8_t> bin;

  // Appends bytes (4-byte aligned) as a new bufferView of buffer 0; returns its index.
  int add_view(const void* data, size_t size, int stride = 0);

  // Adds an accessor (view -1: none, read as zeros); returns its index.
  int add_accessor(int view, int component_type, size_t count, const std::string& type, size_t offset = 0,
                   bool normalized = false);

  // A tightly packed accessor holding `values` of the given component type.
  template <typename T>
  int add_data(const std::vector<T>& values, int component_type, const std::string& type, size_t components,
               bool normalized = false) {
    const int view = add_view(values.data(), values.size() * sizeof(T));
    return add_accessor(view, component_type, values.size() / components, type, 0, normalized);
  }

  // FLOAT VEC3 positions, x y z per vertex.
  int add_positions(const std::vector<float>& xyz);

  // A mesh with one primitive given as JSON; returns the mesh index.
  int add_mesh(const nlohmann::json& primitive);

  // A mesh with one TRIANGLES primitive of uint32 indices (NORMAL and TEXCOORD_0 when given),
  // POSITION with its min and max; returns the mesh index.
  int add_mesh(const std::vector<std::array<float, 3>>& positions, const std::vector<uint32_t>& indices,
               int material = -1, const std::vector<std::array<float, 3>>& normals = {},
               const std::vector<std::array<float, 2>>& texcoords = {});

  // Each returns the new element's index.
  int add_material(const nlohmann::json& material);
  int add_node(const nlohmann::json& node);
  int add_camera(const nlohmann::json& camera);
  int add_light(const nlohmann::json& light);  // KHR_lights_punctual, declared in extensionsUsed

  void add_child(int parent, int child);

  // A node holding a point light of intensity candela at light, and a node with a perspective
  // camera (yfov radians, znear 0.1) at camera looking down -Z: the set-up of the layer tests.
  void add_lamp_and_camera(const std::array<double, 3>& light, double intensity,
                           const std::array<double, 3>& camera, double yfov);

  // Scene 0, the default scene, with these root nodes.
  void set_scene(const std::vector<int>& roots);

  // The document as written: buffer 0 declared (with `uri` unless empty) when there are bytes,
  // and, unless the document lists scenes itself, scene 0 holding every node that is nobody's child.
  nlohmann::json finished(const std::string& uri) const;

  // Writes a .gltf with the buffer as a base64 data URI; returns the path.
  std::string write(const std::string& path) const;

  // Writes a .gltf whose buffer is the file bin_name beside it (written unless write_bin is false).
  std::string write_external(const std::string& path, const std::string& bin_name,
                             bool write_bin = true) const;

  // The GLB bytes of the document (buffer 0 in the BIN chunk).
  std::vector<uint8_t> glb_bytes() const;
};

// base64 for data URIs.
std::string base64_encode(const std::vector<uint8_t>& bytes);

}  // namespace kiln::testing
