#include "io/gltf/gltf_image_use.h"

#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "core/message_text.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

using json = nlohmann::json;

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// An index as a JSON value may hold it; -1 for anything else (validation refuses those later).
int64_t index_of(const json& value) {
  if (value.is_number_unsigned()) return static_cast<int64_t>(value.get<uint64_t>());
  if (value.is_number_integer()) return value.get<int64_t>();
  if (value.is_number_float() && value.get<double>() >= 0.0 && value.get<double>() < 9e18)
    return static_cast<int64_t>(value.get<double>());
  return -1;
}

// Collects the "index" of every textureInfo below value. The depth of the JSON was already
// limited (--max-json-depth), so the recursion is bounded.
void collect_texture_indices(const json& value, bool is_texture_info, std::vector<int64_t>& out) {
  if (value.is_object()) {
    if (is_texture_info) {
      auto index = value.find("index");
      if (index != value.end()) out.push_back(index_of(*index));
    }
    for (auto it = value.begin(); it != value.end(); ++it)
      collect_texture_indices(it.value(), ends_with(it.key(), "Texture"), out);
  } else if (value.is_array()) {
    for (const json& item : value) collect_texture_indices(item, false, out);
  }
}

// An image's or buffer's URI as a file path, or "" for data URIs and anything that is no string.
std::string external_uri(const json& item) {
  if (!item.is_object()) return "";
  auto uri = item.find("uri");
  if (uri == item.end() || !uri->is_string()) return "";
  const std::string text = uri->get<std::string>();
  return text.empty() || text.rfind("data:", 0) == 0 ? "" : text;
}

// tinygltf decodes image URIs with dlib's urldecode, which also turns '+' into a space;
// kiln's percent_decoded leaves '+'. A file either decoding names is kept readable.
std::string plus_as_space(std::string uri) {
  for (char& c : uri)
    if (c == '+') c = ' ';
  return uri;
}

}  // namespace

std::string canonical_key(const std::string& path) {
  std::error_code ec;
  const std::string resolved = std::filesystem::weakly_canonical(std::filesystem::path(path), ec).string();
  return ec ? path : resolved;
}

std::vector<bool> images_used_by_materials(const json& doc) {
  auto images = doc.find("images");
  if (images == doc.end() || !images->is_array()) return {};
  std::vector<bool> used(images->size(), false);
  auto materials = doc.find("materials");
  auto textures = doc.find("textures");
  if (materials == doc.end() || textures == doc.end() || !textures->is_array()) return used;
  std::vector<int64_t> texture_indices;
  collect_texture_indices(*materials, false, texture_indices);
  for (int64_t t : texture_indices) {
    if (t < 0 || static_cast<size_t>(t) >= textures->size()) continue;
    const json& texture = (*textures)[static_cast<size_t>(t)];
    if (!texture.is_object()) continue;
    // The image the loader will decode (gltf_materials.cpp): EXT_texture_webp's source where the
    // texture has one, else "source" (a KHR_texture_basisu texture falls back to it too).
    const json* webp = texture.contains("extensions") && texture["extensions"].is_object() &&
                               texture["extensions"].contains("EXT_texture_webp") &&
                               texture["extensions"]["EXT_texture_webp"].is_object() &&
                               texture["extensions"]["EXT_texture_webp"].contains("source")
                           ? &texture["extensions"]["EXT_texture_webp"]["source"]
                           : nullptr;
    if (!webp && !texture.contains("source")) continue;
    const int64_t source = index_of(webp ? *webp : texture["source"]);
    if (source >= 0 && static_cast<size_t>(source) < used.size()) used[static_cast<size_t>(source)] = true;
  }
  return used;
}

std::set<std::string> unused_image_files(const json& doc, const std::vector<bool>& used,
                                         const std::string& folder_prefix) {
  std::set<std::string> unused, needed;
  const auto key = [&](const std::string& uri, bool plus_decoded) {
    return canonical_key(folder_prefix + percent_decoded(plus_decoded ? plus_as_space(uri) : uri));
  };
  for (const char* collection : {"buffers", "images"}) {
    auto items = doc.find(collection);
    if (items == doc.end() || !items->is_array()) continue;
    for (size_t i = 0; i < items->size(); ++i) {
      const std::string uri = external_uri((*items)[i]);
      if (uri.empty()) continue;
      const bool is_unused_image = collection == std::string("images") && i < used.size() && !used[i];
      if (is_unused_image) {
        unused.insert(key(uri, true));
      } else {
        needed.insert(key(uri, true));
        needed.insert(key(uri, false));
      }
    }
  }
  for (const std::string& file : needed) unused.erase(file);
  return unused;
}

void refuse_missing_image_files(const json& doc, const std::string& folder_prefix, const std::string& file) {
  auto images = doc.find("images");
  if (images == doc.end() || !images->is_array()) return;
  for (size_t i = 0; i < images->size(); ++i) {
    const std::string uri = external_uri((*images)[i]);
    if (uri.empty()) continue;
    std::error_code ec;
    // tinygltf tries the URI with '+' as a space and as itself; either file will do.
    if (std::filesystem::exists(folder_prefix + percent_decoded(plus_as_space(uri)), ec) ||
        std::filesystem::exists(folder_prefix + percent_decoded(uri), ec))
      continue;
    throw input_error(file, "/images/" + std::to_string(i) + "/uri", "cannot read image file " + quoted(uri));
  }
}

}  // namespace kiln::gltf_internal
