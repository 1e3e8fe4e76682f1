// The material extensions that add lobes to the glTF BRDF (KHR_materials_clearcoat, _sheen,
// _iridescence, _anisotropy, _diffuse_transmission and _dispersion) read into kiln's material:
// factors checked against their specifications' ranges, textures resolved like the core ones.
// Internal to io/gltf; called by convert_material.
#pragma once

#include <tiny_gltf.h>

#include <string>

#include "io/gltf/gltf_materials.h"

namespace kiln::gltf_internal {

// Reads src's lobe extensions into m; ext_where is the JSON pointer of src's "extensions".
void convert_material_lobes(const tinygltf::Model& model, const tinygltf::Material& src, material& m,
                            texture_remap& remap, scene& out, const std::string& file,
                            const std::string& ext_where);

}  // namespace kiln::gltf_internal
