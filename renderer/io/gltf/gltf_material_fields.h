// Readers for the members of glTF material extensions, each validated where it is read: a bad
// value throws kiln::error (input) naming the file and the member's JSON pointer. Shared by the
// core material conversion (gltf_materials.cpp) and the lobe extensions' (gltf_material_lobes.cpp).
// Internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <string>

#include "io/gltf/gltf_materials.h"

namespace kiln::gltf_internal {

// Throws input_error(file, where, reason) unless ok.
void require(bool ok, const std::string& file, const std::string& where, const std::string& reason);

// The extension object `name` of a material, or null.
const tinygltf::Value* find_extension(const tinygltf::Material& m, const char* name);

// Reads a number member of an extension object; false when absent or not a number.
bool extension_number(const tinygltf::Value& object, const char* key, double& out);

// Reads a number member that must lie in [low, high] when present; false when absent.
bool bounded_number(const tinygltf::Value& object, const char* key, double low, double high, double& out,
                    const std::string& file, const std::string& where);

// Reads an RGB member ([r, g, b], finite, not negative) when present.
void color_member(const tinygltf::Value& object, const char* key, vec3& out, const std::string& file,
                  const std::string& where);

// A textureInfo (or normalTextureInfo: its scale too) inside a material extension, validated like
// the core ones; absent: no texture.
texture_ref extension_texture(const tinygltf::Model& model, const tinygltf::Value& ext, const char* key,
                              texture_remap& remap, scene& out, const std::string& file,
                              const std::string& where);

}  // namespace kiln::gltf_internal
