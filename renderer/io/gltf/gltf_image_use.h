// Which images of a glTF file a material can sample, read from the raw JSON before tinygltf
// runs, so that image files nothing samples are never read nor kept in memory. Internal to io/gltf.
#pragma once

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// used[i] is true when some material's textureInfo (any object under /materials/* whose key ends
// in "Texture", extensions included) names a texture whose "source" is image i. Conservative:
// an image of a material no mesh uses still counts as used.
std::vector<bool> images_used_by_materials(const nlohmann::json& doc);

// The image files (canonical paths, as read_whole_file sees them) of images that are not used and
// whose file no buffer and no used image also names: those need not be read. folder_prefix is the
// canonical asset folder ending in '/'.
std::set<std::string> unused_image_files(const nlohmann::json& doc, const std::vector<bool>& used,
                                         const std::string& folder_prefix);

// Throws kiln::error (input) naming file and /images/i/uri when an external image's file does not
// exist, used or not: a broken reference is an error even where its bytes would not be read.
void refuse_missing_image_files(const nlohmann::json& doc, const std::string& folder_prefix,
                                const std::string& file);

// The canonical form of a path, the key of unused_image_files(); the path itself when it cannot
// be resolved.
std::string canonical_key(const std::string& path);

}  // namespace kiln::gltf_internal
