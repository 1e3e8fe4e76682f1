// Decodes encoded glTF images (PNG, JPEG, ...) from memory with OpenImageIO into kiln images:
// 8-bit RGBA for 8-bit sources, float RGBA for deeper ones, row 0 at the top. Internal to
// io/gltf; the only file that includes OpenImageIO.
#pragma once

#include "scene/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kiln::gltf_internal {

// Decodes `encoded` (the format is recognised from its magic bytes, not from names or MIME
// types). Alpha stays straight (unassociated), as glTF stores it. Throws kiln::error (input)
// naming `file` and `where` (e.g. /images/3) when the data is not a decodable image.
// An image whose header declares more than max_texels texels is refused before it is decoded.
image decode_image(const std::vector<uint8_t>& encoded, const std::string& name, const std::string& file,
                   const std::string& where, uint64_t max_texels = uint64_t(1) << 28);

}  // namespace kiln::gltf_internal
