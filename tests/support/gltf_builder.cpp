#include "support/gltf_builder.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace kiln::testing {
namespace {

using nlohmann::json;

int push(json& list, const json& item) {
  list.push_back(item);
  return static_cast<int>(list.size() - 1);
}

void write_file(const std::string& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + path);
}

// Nodes that no node lists among its children, in document order.
json root_nodes(const json& doc) {
  const size_t count = doc.contains("nodes") && doc["nodes"].is_array() ? doc["nodes"].size() : 0;
  std::vector<bool> is_child(count, false);
  for (size_t n = 0; n < count; ++n) {
    const json& node = doc["nodes"][n];
    if (!node.is_object() || !node.contains("children") || !node["children"].is_array()) continue;
    for (const json& c : node["children"])
      if (c.is_number_integer() && c.get<int64_t>() >= 0 && uint64_t(c.get<int64_t>()) < count)
        is_child[c.get<size_t>()] = true;
  }
  json roots = json::array();
  for (size_t n = 0; n < count; ++n)
    if (!is_child[n]) roots.push_back(n);
  return roots;
}

}  // namespace

std::string base64_encode(const std::vector<uint8_t>& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    for (int k = 3; k >= 0; --k) out += alphabet[(v >> (6 * k)) & 63];
  }
  const size_t rest = bytes.size() - i;  // 0, 1 or 2 bytes left: pad to a whole quantum
  if (rest > 0) {
    const uint32_t v = (uint32_t(bytes[i]) << 16) | (rest == 2 ? uint32_t(bytes[i + 1]) << 8 : 0);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += rest == 2 ? alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

int gltf_builder::add_view(const void* data, size_t size, int stride) {
  while (bin.size() % 4 != 0) bin.push_back(0);
  json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
  if (stride != 0) view["byteStride"] = stride;
  const auto* p = static_cast<const uint8_t*>(data);
  bin.insert(bin.end(), p, p + size);
  return push(doc["bufferViews"], view);
}

int gltf_builder::add_accessor(int view, int component_type, size_t count, const std::string& type,
                               size_t offset, bool normalized) {
  json acc = {{"componentType", component_type}, {"count", count}, {"type", type}};
  if (view >= 0) acc["bufferView"] = view;
  if (offset != 0) acc["byteOffset"] = offset;
  if (normalized) acc["normalized"] = true;
  return push(doc["accessors"], acc);
}

int gltf_builder::add_positions(const std::vector<float>& xyz) { return add_data(xyz, 5126, "VEC3", 3); }

int gltf_builder::add_mesh(const json& primitive) {
  return push(doc["meshes"], json{{"primitives", json::array({primitive})}});
}

int gltf_builder::add_mesh(const std::vector<std::array<float, 3>>& positions,
                           const std::vector<uint32_t>& indices, int material,
                           const std::vector<std::array<float, 3>>& normals,
                           const std::vector<std::array<float, 2>>& texcoords) {
  std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (const auto& p : positions)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  // A vertex attribute: its view is an ARRAY_BUFFER (34962).
  const auto attribute = [&](const void* data, size_t count, size_t components, const char* type) {
    const int view = add_view(data, count * components * sizeof(float));
    doc["bufferViews"][view]["target"] = 34962;
    return add_accessor(view, 5126, count, type);
  };
  json primitive;
  const int position = attribute(positions.data(), positions.size(), 3, "VEC3");
  doc["accessors"][position]["min"] = lo;
  doc["accessors"][position]["max"] = hi;
  primitive["attributes"]["POSITION"] = position;
  if (!normals.empty())
    primitive["attributes"]["NORMAL"] = attribute(normals.data(), normals.size(), 3, "VEC3");
  if (!texcoords.empty())
    primitive["attributes"]["TEXCOORD_0"] = attribute(texcoords.data(), texcoords.size(), 2, "VEC2");
  const int index_view = add_view(indices.data(), indices.size() * sizeof(uint32_t));
  doc["bufferViews"][index_view]["target"] = 34963;  // ELEMENT_ARRAY_BUFFER
  primitive["indices"] = add_accessor(index_view, 5125, indices.size(), "SCALAR");
  if (material >= 0) primitive["material"] = material;
  return add_mesh(primitive);
}

int gltf_builder::add_material(const json& material) { return push(doc["materials"], material); }
int gltf_builder::add_node(const json& node) { return push(doc["nodes"], node); }
int gltf_builder::add_camera(const json& camera) { return push(doc["cameras"], camera); }

int gltf_builder::add_light(const json& light) {
  json& used = doc["extensionsUsed"];
  if (std::find(used.begin(), used.end(), "KHR_lights_punctual") == used.end())
    used.push_back("KHR_lights_punctual");
  return push(doc["extensions"]["KHR_lights_punctual"]["lights"], light);
}

void gltf_builder::add_lamp_and_camera(const std::array<double, 3>& light, double intensity,
                                       const std::array<double, 3>& camera, double yfov) {
  const int lamp = add_light({{"type", "point"}, {"name", "lamp"}, {"intensity", intensity}});
  add_node({{"name", "lamp"},
            {"extensions", {{"KHR_lights_punctual", {{"light", lamp}}}}},
            {"translation", light}});
  add_camera({{"type", "perspective"}, {"perspective", {{"yfov", yfov}, {"znear", 0.1}}}});
  add_node({{"camera", int(doc["cameras"].size()) - 1}, {"translation", camera}});
}

void gltf_builder::add_child(int parent, int child) { doc["nodes"][parent]["children"].push_back(child); }

void gltf_builder::set_scene(const std::vector<int>& roots) {
  doc["scenes"] = json::array({json{{"nodes", roots}}});
  doc["scene"] = 0;
}

json gltf_builder::finished(const std::string& uri) const {
  json out = doc;
  if (!bin.empty()) {
    out["buffers"] = json::array({json{{"byteLength", bin.size()}}});
    if (!uri.empty()) out["buffers"][0]["uri"] = uri;
  }
  if (!out.contains("scenes")) {
    out["scenes"] = json::array({json{{"nodes", root_nodes(out)}}});
    out["scene"] = 0;
  }
  return out;
}

std::string gltf_builder::write(const std::string& path) const {
  const std::string text = finished("data:application/octet-stream;base64," + base64_encode(bin)).dump(1);
  write_file(path, text.data(), text.size());
  return path;
}

std::string gltf_builder::write_external(const std::string& path, const std::string& bin_name,
                                         bool write_bin) const {
  const std::string text = finished(bin_name).dump(1);
  write_file(path, text.data(), text.size());
  if (write_bin) {
    const size_t slash = path.find_last_of('/');
    write_file((slash == std::string::npos ? "" : path.substr(0, slash + 1)) + bin_name, bin.data(),
               bin.size());
  }
  return path;
}

std::vector<uint8_t> gltf_builder::glb_bytes() const {
  std::string text = finished("").dump();
  while (text.size() % 4 != 0) text += ' ';
  std::vector<uint8_t> payload = bin;
  while (payload.size() % 4 != 0) payload.push_back(0);
  std::vector<uint8_t> out;
  const auto u32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  const uint32_t total = 12 + 8 + static_cast<uint32_t>(text.size()) +
                         (payload.empty() ? 0 : 8 + static_cast<uint32_t>(payload.size()));
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(total);
  u32(static_cast<uint32_t>(text.size()));
  u32(0x4E4F534A);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  if (!payload.empty()) {
    u32(static_cast<uint32_t>(payload.size()));
    u32(0x004E4942);  // "BIN\0"
    out.insert(out.end(), payload.begin(), payload.end());
  }
  return out;
}

}  // namespace kiln::testing
