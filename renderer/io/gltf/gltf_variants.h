// KHR_materials_variants: a file's named material variants (a product's colourways) and its
// primitives' mappings from variants to materials. Choosing a variant rewrites each mapped
// primitive's material before the scene is built, so everything downstream (which UV sets and
// tangents a mesh keeps, the materials converted, the ids) follows the variant's materials exactly
// as if the file had named them. Internal to io/gltf; bad input throws kiln::error (input) with
// the JSON pointer, e.g. /meshes/0/primitives/0/extensions/KHR_materials_variants/mappings/1/material.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace kiln::gltf_internal {

constexpr const char* variants_extension = "KHR_materials_variants";

// The variants' names in file order (empty when the file has none); checks the root list.
std::vector<std::string> material_variant_names(const tinygltf::Model& model, const std::string& file);

// Checks every primitive's mappings (materials and variants in range) and, when `which` names a
// variant (its name, or its index), gives each primitive that variant's material. "" chooses none:
// every primitive keeps its own material. An unknown variant, or one asked of a file without
// variants, throws kiln::error (input, location --variant) naming the known ones.
void apply_material_variant(tinygltf::Model& model, const std::string& which, const std::string& file);

}  // namespace kiln::gltf_internal
