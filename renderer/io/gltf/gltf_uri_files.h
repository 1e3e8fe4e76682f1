// The one rule for the files a glTF asset's buffer and image URIs name. The loader applies it
// before tinygltf runs, and the input fingerprint (batch resume, EXR metadata) before it hashes a
// byte, so neither reads a file the other would refuse: an absolute URI, one that leaves the
// asset's folder, or one naming a FIFO or a device, whose reading never ends. Internal to io/gltf.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// Where URIs may lead, for one asset.
struct uri_rules {
  std::string folder_prefix;   // the canonical asset folder (symlinks resolved), ending in '/'
  bool allow_outside = false;  // --allow-outside-files: ".." and symlinks may leave the folder
};

// The rules for the asset at asset_path. Throws kiln::error (input) when its folder cannot be
// resolved.
uri_rules asset_uri_rules(const std::string& asset_path, bool allow_outside);

// True when path, with ".", ".." and symbolic links resolved, lies inside the rules' folder.
bool inside_asset_folder(const std::string& path, const uri_rules& rules);

// Calls visit(pointer, uri) for the raw "uri" of every buffer and image that is a string other
// than a data URI, in the order the JSON lists them; pointer is e.g. /buffers/0/uri.
void for_each_file_uri(const nlohmann::json& doc,
                       const std::function<void(const std::string& pointer, const std::string& uri)>& visit);

// Checks one file URI (raw, as in the JSON) of asset and returns the paths it may name that
// exist: percent-decoded, and also with '+' read as a space, as tinygltf decodes. Throws
// kiln::error (input) naming asset and pointer for an absolute path or file: URI (always), a
// path outside the folder (unless allowed), and a path that exists but is not a regular file (a
// FIFO, a device, a folder) or is over kiln's file size limit. A missing file is not refused
// here: the loader's later checks name it in their own words.
std::vector<std::string> checked_uri_files(const std::string& asset, const std::string& pointer,
                                           const std::string& uri, const uri_rules& rules);

}  // namespace kiln::gltf_internal
