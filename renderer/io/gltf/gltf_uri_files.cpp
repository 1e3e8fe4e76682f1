#include "io/gltf/gltf_uri_files.h"

#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "core/message_text.h"
#include "io/file/input_file.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_loader.h"

namespace kiln::gltf_internal {

namespace fs = std::filesystem;

uri_rules asset_uri_rules(const std::string& asset_path, bool allow_outside) {
  std::error_code ec;
  const fs::path folder = fs::absolute(fs::path(asset_path), ec).parent_path();
  if (ec) throw input_error(asset_path, "", "cannot resolve the asset's folder: " + ec.message());
  uri_rules rules;
  rules.folder_prefix = fs::weakly_canonical(folder, ec).string();
  if (ec) throw input_error(asset_path, "", "cannot resolve the asset's folder: " + ec.message());
  if (rules.folder_prefix.empty() || rules.folder_prefix.back() != '/') rules.folder_prefix += '/';
  rules.allow_outside = allow_outside;
  return rules;
}

// A scene file must not read arbitrary files (../../etc/passwd) on a render farm node, and
// neither may a symlink that sits in the folder but points out of it.
bool inside_asset_folder(const std::string& path, const uri_rules& rules) {
  std::error_code ec;
  const std::string resolved = fs::weakly_canonical(fs::path(path), ec).string();
  if (ec) return false;
  return resolved.compare(0, rules.folder_prefix.size(), rules.folder_prefix) == 0;
}

void for_each_file_uri(const nlohmann::json& doc,
                       const std::function<void(const std::string& pointer, const std::string& uri)>& visit) {
  if (!doc.is_object()) return;
  for (const char* collection : {"buffers", "images"}) {
    auto items = doc.find(collection);
    if (items == doc.end() || !items->is_array()) continue;
    for (size_t i = 0; i < items->size(); ++i) {
      const nlohmann::json& item = (*items)[i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (percent_decoded(uri).rfind("data:", 0) == 0) continue;
      visit(pointer_join(pointer(collection, static_cast<int64_t>(i)), "uri"), uri);
    }
  }
}

namespace {

// True when no file system could hold a file by this name: a component past NAME_MAX (255 bytes
// on Linux file systems) or the whole past PATH_MAX. Such a name is refused for what it is, not as
// a file outside the folder (which is what a failed canonicalisation would otherwise report).
bool name_too_long(const std::string& name) {
  if (name.size() >= 4096) return true;
  size_t start = 0;
  while (start <= name.size()) {
    size_t end = name.find('/', start);
    if (end == std::string::npos) end = name.size();
    if (end - start > 255) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

std::vector<std::string> checked_uri_files(const std::string& asset, const std::string& pointer,
                                           const std::string& uri, const uri_rules& rules) {
  const std::string decoded = percent_decoded(uri);
  if (decoded.rfind("file:", 0) == 0 || fs::path(decoded).is_absolute())
    throw input_error(asset, pointer,
                      quoted(decoded) + " is an absolute path; glTF URIs are relative to the asset");
  if (name_too_long(decoded))
    throw input_error(asset, pointer,
                      quoted(decoded) + " cannot name a file (a path component is longer than 255 bytes)");
  // tinygltf decodes with dlib's urldecode, which also reads '+' as a space: both spellings count.
  std::string plus_as_space = uri;
  for (char& c : plus_as_space)
    if (c == '+') c = ' ';
  std::vector<std::string> names{decoded};
  if (percent_decoded(plus_as_space) != decoded) names.push_back(percent_decoded(plus_as_space));
  std::vector<std::string> files;
  for (const std::string& name : names) {
    const std::string path = rules.folder_prefix + name;
    if (!rules.allow_outside && !inside_asset_folder(path, rules))
      throw input_error(
          asset, pointer,
          quoted(decoded) +
              " refers to a file outside the asset's folder (allow with --allow-outside-files)");
    if (input_file_missing(path)) continue;
    if (const std::string why = input_file_problem(path, max_gltf_file_bytes); !why.empty())
      throw input_error(asset, pointer, quoted(decoded) + " " + why);
    files.push_back(path);
  }
  return files;
}

}  // namespace kiln::gltf_internal
