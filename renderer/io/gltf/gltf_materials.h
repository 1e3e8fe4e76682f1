// glTF materials, textures, samplers and images to kiln's scene types. Only what used materials
// reference is converted: textures and images get new, dense indices, and unused images are
// never decoded. Images are queued while materials convert and decoded together, in parallel.
// Internal to io/gltf; runs after gltf_validate.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "core/memory_budget.h"
#include "io/gltf/gltf_images.h"
#include "scene/scene.h"

namespace kiln::gltf_internal {

// glTF texture/image index -> scene index, filled as materials are converted (-1: not yet).
struct texture_remap {
  std::vector<int32_t> textures;
  std::vector<int32_t> images;
  std::vector<char> missing_source_warned;  // per glTF texture: warned once about a missing source
  uint64_t max_texels = uint64_t(1) << 28;  // gltf_limits::max_texels
  memory_budget* memory = nullptr;          // decoded images are charged here; null: none
  // Images given a scene index but not decoded yet, in scene order; they are the last
  // pending.size() entries of scene::images, placeholders until decode_used_images.
  std::vector<encoded_image> pending;
};

texture_remap make_texture_remap(const tinygltf::Model& model);

// Converts glTF material `index`, appending the textures and images it references to `out` (the
// images as placeholders, queued in remap.pending). Throws kiln::error (input) for non-finite or
// out-of-range factors.
material convert_material(const tinygltf::Model& model, int index, texture_remap& remap, scene& out,
                          const std::string& file);

// Decodes the queued images into their places in out.images on `threads` threads (0: all cores).
// Throws kiln::error (input) naming the first undecodable one in scene order.
void decode_used_images(texture_remap& remap, scene& out, const std::string& file, int threads);

// The glTF default material: white, metallic 1, roughness 1, opaque, single-sided.
material default_material();

// True when a glTF material samples any texture through TEXCOORD_0.
bool material_samples_texcoord0(const tinygltf::Model& model, int material_index);

// True when a glTF material samples any texture through TEXCOORD_<set> (after
// KHR_texture_transform's texCoord override), or its tangent frame follows that set.
bool material_samples_texcoord(const tinygltf::Model& model, int material_index, int set);

// The UV set a material's tangent frame follows (after KHR_texture_transform's texCoord
// override): the normal texture's, else the clearcoat normal texture's, else the anisotropy
// texture's (0 for anisotropy without one); -1 when the material reads no tangent frame.
int material_tangent_texcoord(const tinygltf::Model& model, int material_index);

// True when a glTF material samples any texture through a TEXCOORD_n with n > 1 (not stored).
bool material_samples_other_texcoords(const tinygltf::Model& model, int material_index);

}  // namespace kiln::gltf_internal
