// Turns a .gltf/.glb file into a tinygltf::Model without trusting anything in it: reads the file
// under a size limit, checks the GLB container itself, runs tinygltf with safe file-system
// callbacks (no shell expansion, no lookups outside the asset's folder) and an image callback
// that keeps encoded bytes instead of decoding, then refuses unsupported versions and required
// extensions. Internal to io/gltf. No scene construction and no validation of references here.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "io/gltf/gltf_loader.h"

namespace kiln::gltf_internal {

// Extensions kiln implements; only these may appear in extensionsRequired.
const std::vector<std::string>& supported_extensions();

// Parses the file at `path`. Images keep their encoded bytes in image.image (as_is = true);
// images stored in a bufferView are left empty, to be read after the bufferView is validated.
// Throws kiln::error (input) for a missing or unreadable file, a broken container, invalid JSON,
// an asset version other than 2.x, an unsupported required extension, or JSON beyond
// options.limits. Buffers and images are read only from inside the asset's folder unless
// options.allow_files_outside_folder is set.
// The file, its JSON parse and its buffers are charged to `held` (which the caller keeps while the
// model lives) before they are read.
tinygltf::Model parse_gltf_file(const std::string& path, const gltf_load_options& options,
                                memory_charge* held = nullptr);

}  // namespace kiln::gltf_internal
