// Readers for the members of glTF material extensions, each validated where it is read: a bad
// value throws kiln::error (input) naming the file and the member's JSON pointer. Shared by the
// core material conversion (gltf_materials.cpp) and the lobe extensions' (gltf_material_lobes.cpp).
// Internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <cmath>
#include <limits>
#include <string>

#include "io/gltf/gltf_materials.h"

namespace kiln::gltf_internal {

// Materials hold floats: a glTF number past this rounds to infinity when stored (an ior of 1e308
// or an emissiveStrength of 3.5e38 shaded as NaN), so no member may exceed it.
constexpr double largest_material_value = std::numeric_limits<float>::max();

// True when v is finite and stays finite as a float.
inline bool fits_float(double v) { return std::abs(v) <= largest_material_value; }

// Throws input_error(file, where, reason) unless ok.
void require(bool ok, const std::string& file, const std::string& where, const std::string& reason);

// The extension object `name` of a material, or null.
const tinygltf::Value* find_extension(const tinygltf::Material& m, const char* name);

// Reads a number member of an extension object; false when absent or not a number.
bool extension_number(const tinygltf::Value& object, const char* key, double& out);

// Reads a number member that must lie in [low, high] when present; false when absent. high is at
// most largest_material_value.
bool bounded_number(const tinygltf::Value& object, const char* key, double low, double high, double& out,
                    const std::string& file, const std::string& where);

// Reads an RGB member ([r, g, b], each a float, not negative) when present.
void color_member(const tinygltf::Value& object, const char* key, vec3& out, const std::string& file,
                  const std::string& where);

// A textureInfo (or normalTextureInfo: its scale too) inside a material extension, validated like
// the core ones; absent: no texture.
texture_ref extension_texture(const tinygltf::Model& model, const tinygltf::Value& ext, const char* key,
                              texture_remap& remap, scene& out, const std::string& file,
                              const std::string& where);

}  // namespace kiln::gltf_internal
