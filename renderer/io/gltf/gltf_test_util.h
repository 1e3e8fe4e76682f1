// Test helpers for the glTF loader: build small glTF documents with nlohmann::json plus one
// binary buffer, and write them into a per-test temporary folder as .gltf (data URI or external
// .bin) or .glb. Tests only; not part of kiln_io_gltf.
#pragma once

#include "core/error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace kiln::gltf_test {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int k_byte = 5120, k_ubyte = 5121, k_short = 5122, k_ushort = 5123, k_uint = 5125, k_float = 5126;

// A 2x2 RGBA8 PNG: red, green / blue, white with alpha 128.
constexpr const char* png_2x2_base64 =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg="
    "=";
// A 1x1 16-bit RGB PNG: (65535, 32768, 0).
constexpr const char* png_16bit_base64 =
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABEAIAAADA54+dAAAAD0lEQVR4nGP4/7+BgYEBAAz8An+jd5TMAAAAAElFTkSuQmCC";

inline std::string base64_encode(const std::vector<uint8_t>& data) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < data.size(); i += 3) {
    const uint32_t v = (uint32_t(data[i]) << 16) | (uint32_t(data[i + 1]) << 8) | data[i + 2];
    for (int k = 3; k >= 0; --k) out += alphabet[(v >> (6 * k)) & 63];
  }
  const size_t rest = data.size() - i;
  if (rest == 1) {
    const uint32_t v = uint32_t(data[i]) << 16;
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += "==";
  } else if (rest == 2) {
    const uint32_t v = (uint32_t(data[i]) << 16) | (uint32_t(data[i + 1]) << 8);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

// A fresh folder per test under the system temp folder, removed when the test ends.
class temp_folder {
 public:
  temp_folder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("kiln_gltf_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(reinterpret_cast<uintptr_t>(this) & 0xffffff));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~temp_folder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  temp_folder(const temp_folder&) = delete;
  temp_folder& operator=(const temp_folder&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Builds a glTF document with a single buffer whose bytes are collected in `bin`.
struct gltf_builder {
  json doc = json{{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;

  // Appends bytes (4-byte aligned) as a new bufferView; returns its index.
  int add_view(const void* data, size_t size, int stride = 0) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (stride != 0) view["byteStride"] = stride;
    const auto* p = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), p, p + size);
    doc["bufferViews"].push_back(view);
    return static_cast<int>(doc["bufferViews"].size() - 1);
  }

  int add_accessor(int view, int component_type, size_t count, const std::string& type, size_t offset = 0,
                   bool normalized = false) {
    json acc = {{"componentType", component_type}, {"count", count}, {"type", type}};
    if (view >= 0) acc["bufferView"] = view;
    if (offset != 0) acc["byteOffset"] = offset;
    if (normalized) acc["normalized"] = true;
    doc["accessors"].push_back(acc);
    return static_cast<int>(doc["accessors"].size() - 1);
  }

  // A tightly packed accessor holding `values` of the given component type.
  template <typename T>
  int add_data(const std::vector<T>& values, int component_type, const std::string& type, size_t components,
               bool normalized = false) {
    const int view = add_view(values.data(), values.size() * sizeof(T));
    return add_accessor(view, component_type, values.size() / components, type, 0, normalized);
  }

  int add_positions(const std::vector<float>& xyz) { return add_data(xyz, k_float, "VEC3", 3); }

  // A mesh with one primitive; returns the mesh index.
  int add_mesh(const json& primitive) {
    doc["meshes"].push_back(json{{"primitives", json::array({primitive})}});
    return static_cast<int>(doc["meshes"].size() - 1);
  }

  int add_node(const json& node) {
    doc["nodes"].push_back(node);
    return static_cast<int>(doc["nodes"].size() - 1);
  }

  void set_scene(const std::vector<int>& roots) {
    doc["scenes"] = json::array({json{{"nodes", roots}}});
    doc["scene"] = 0;
  }

  // The document with its buffer declared (bytes not yet attached).
  json finished(const std::string& uri) const {
    json out = doc;
    if (!bin.empty()) {
      out["buffers"] = json::array({json{{"byteLength", bin.size()}}});
      if (!uri.empty()) out["buffers"][0]["uri"] = uri;
    }
    return out;
  }

  // Writes a .gltf with the buffer as a base64 data URI; returns the path.
  std::string write_gltf(const temp_folder& folder, const std::string& name = "scene.gltf") const {
    const std::string path = folder.file(name);
    write_text(path, finished("data:application/octet-stream;base64," + base64_encode(bin)).dump(2));
    return path;
  }

  // Writes a .gltf plus an external .bin next to it.
  std::string write_gltf_external(const temp_folder& folder, const std::string& name,
                                  const std::string& bin_name, bool write_bin = true) const {
    const std::string path = folder.file(name);
    write_text(path, finished(bin_name).dump(2));
    if (write_bin) write_bytes(folder.file(bin_name), bin);
    return path;
  }

  // The GLB bytes of the document (buffer 0 in the BIN chunk).
  std::vector<uint8_t> glb_bytes() const {
    std::string text = finished("").dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<uint8_t> payload = bin;
    while (payload.size() % 4 != 0) payload.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    };
    const uint32_t total = 12 + 8 + static_cast<uint32_t>(text.size()) +
                           (payload.empty() ? 0 : 8 + static_cast<uint32_t>(payload.size()));
    u32(0x46546C67);
    u32(2);
    u32(total);
    u32(static_cast<uint32_t>(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!payload.empty()) {
      u32(static_cast<uint32_t>(payload.size()));
      u32(0x004E4942);
      out.insert(out.end(), payload.begin(), payload.end());
    }
    return out;
  }
};

// A builder holding one triangle mesh (positions + u16 indices) placed by one node.
inline gltf_builder single_triangle() {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2}, k_ushort, "SCALAR", 1);
  const int mesh = b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.set_scene({b.add_node({{"mesh", mesh}})});
  return b;
}

// Loads `path` expecting kiln::error; returns its message ("" and a test failure when it loads).
template <typename Load>
std::string error_of(Load load) {
  try {
    load();
  } catch (const kiln::error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected kiln::error, but the file loaded";
  return "";
}

}  // namespace kiln::gltf_test
