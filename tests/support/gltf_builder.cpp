#include "support/gltf_builder.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace kiln::testing {

std::string base64_encode(const std::vector<uint8_t>& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    for (int k = 3; k >= 0; --k) out += alphabet[(v >> (6 * k)) & 63];
  }
  if (i + 1 == bytes.size()) {
    uint32_t v = bytes[i] << 16;
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

gltf_builder::gltf_builder() {
  doc_["asset"] = {{"version", "2.0"}, {"generator", "kiln tests"}};
  doc_["scene"] = 0;
}

int gltf_builder::add_accessor(const void* data, size_t bytes, int component_type, const char* type, size_t count,
                               int target, const nlohmann::json& min, const nlohmann::json& max) {
  while (buffer_.size() % 4) buffer_.push_back(0);
  size_t offset = buffer_.size();
  buffer_.resize(offset + bytes);
  std::memcpy(buffer_.data() + offset, data, bytes);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}};
  doc_["bufferViews"].push_back(view);
  nlohmann::json accessor = {{"bufferView", doc_["bufferViews"].size() - 1},
                             {"componentType", component_type},
                             {"count", count},
                             {"type", type}};
  if (!min.is_null()) accessor["min"] = min;
  if (!max.is_null()) accessor["max"] = max;
  doc_["accessors"].push_back(accessor);
  return int(doc_["accessors"].size() - 1);
}

int gltf_builder::add_mesh(const std::vector<std::array<float, 3>>& positions, const std::vector<uint32_t>& indices,
                           int material, const std::vector<std::array<float, 3>>& normals,
                           const std::vector<std::array<float, 2>>& texcoords) {
  std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (const auto& p : positions)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  nlohmann::json primitive;
  primitive["attributes"]["POSITION"] = add_accessor(positions.data(), positions.size() * 12, 5126, "VEC3",
                                                     positions.size(), 34962, lo, hi);
  if (!normals.empty())
    primitive["attributes"]["NORMAL"] =
        add_accessor(normals.data(), normals.size() * 12, 5126, "VEC3", normals.size(), 34962);
  if (!texcoords.empty())
    primitive["attributes"]["TEXCOORD_0"] =
        add_accessor(texcoords.data(), texcoords.size() * 8, 5126, "VEC2", texcoords.size(), 34962);
  primitive["indices"] = add_accessor(indices.data(), indices.size() * 4, 5125, "SCALAR", indices.size(), 34963);
  if (material >= 0) primitive["material"] = material;
  doc_["meshes"].push_back({{"primitives", {primitive}}});
  return int(doc_["meshes"].size() - 1);
}

int gltf_builder::add_material(const nlohmann::json& material) {
  doc_["materials"].push_back(material);
  return int(doc_["materials"].size() - 1);
}

int gltf_builder::add_node(const nlohmann::json& node) {
  doc_["nodes"].push_back(node);
  is_child_.push_back(false);
  return int(doc_["nodes"].size() - 1);
}

void gltf_builder::add_child(int parent, int child) {
  doc_["nodes"][parent]["children"].push_back(child);
  is_child_[child] = true;
}

int gltf_builder::add_light(const nlohmann::json& light) {
  auto& lights = doc_["extensions"]["KHR_lights_punctual"]["lights"];
  lights.push_back(light);
  auto& used = doc_["extensionsUsed"];
  if (std::find(used.begin(), used.end(), "KHR_lights_punctual") == used.end()) used.push_back("KHR_lights_punctual");
  return int(lights.size() - 1);
}

int gltf_builder::add_camera(const nlohmann::json& camera) {
  doc_["cameras"].push_back(camera);
  return int(doc_["cameras"].size() - 1);
}

void gltf_builder::write(const std::string& path) {
  doc_["buffers"] = nlohmann::json::array();
  doc_["buffers"].push_back({{"byteLength", buffer_.size()},
                             {"uri", "data:application/octet-stream;base64," + base64_encode(buffer_)}});
  nlohmann::json roots = nlohmann::json::array();
  for (size_t i = 0; i < is_child_.size(); ++i)
    if (!is_child_[i]) roots.push_back(i);
  doc_["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << doc_.dump(1);
}

}  // namespace kiln::testing
