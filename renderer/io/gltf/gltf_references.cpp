#include "io/gltf/gltf_references.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/gltf/glb_container.h"
#include "io/gltf/gltf_common.h"

namespace kiln {

namespace fs = std::filesystem;

std::vector<std::string> gltf_referenced_files(const std::string& asset_path) {
  std::ifstream in(asset_path, std::ios::binary);
  if (!in) return {};
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const uint8_t* text = bytes.data();
  size_t size = bytes.size();
  if (gltf_internal::has_glb_magic(bytes)) {
    try {
      const gltf_internal::glb_layout layout = gltf_internal::check_glb_container(bytes, asset_path);
      text += layout.json_offset;
      size = layout.json_length;
    } catch (const error&) {
      return {};
    }
  }
  const nlohmann::json doc = nlohmann::json::parse(text, text + size, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return {};
  const fs::path folder = fs::path(asset_path).parent_path();
  std::vector<std::string> files;
  for (const char* collection : {"buffers", "images"}) {
    auto items = doc.find(collection);
    if (items == doc.end() || !items->is_array()) continue;
    for (const nlohmann::json& item : *items) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = gltf_internal::percent_decoded(item["uri"].get<std::string>());
      if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
      files.push_back((folder / uri).string());
    }
  }
  return files;
}

}  // namespace kiln
