#include "io/gltf/gltf_compressed_json.h"

#include "io/gltf/gltf_draco.h"
#include "io/gltf/gltf_meshopt.h"

namespace kiln::gltf_internal {

bool add_compression_placeholders(nlohmann::json& doc, const std::string& file) {
  const bool draco = lend_draco_index_views(doc, file);
  const bool meshopt = fill_meshopt_fallback_buffers(doc);
  return draco || meshopt;
}

}  // namespace kiln::gltf_internal
