#include "io/gltf/gltf_references.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/file/input_file.h"
#include "io/gltf/glb_container.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_memory.h"
#include "io/gltf/gltf_uri_files.h"

namespace kiln {

std::vector<std::string> gltf_referenced_files(const std::string& asset_path,
                                               const gltf_load_options& options) {
  const std::vector<uint8_t> bytes = read_whole_input_file(asset_path, {max_gltf_file_bytes, options.cancel});
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
  if (size > options.limits.max_json_bytes) return {};
  if (options.memory &&
      gltf_internal::json_parse_bytes(text, size) > options.memory->limit() - options.memory->used())
    return {};
  const nlohmann::json doc = nlohmann::json::parse(text, text + size, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return {};
  const gltf_internal::uri_rules rules =
      gltf_internal::asset_uri_rules(asset_path, options.allow_files_outside_folder);
  std::vector<std::string> files;
  gltf_internal::for_each_file_uri(doc, [&](const std::string& pointer, const std::string& uri) {
    for (std::string& file : gltf_internal::checked_uri_files(asset_path, pointer, uri, rules))
      files.push_back(std::move(file));
  });
  return files;
}

}  // namespace kiln
