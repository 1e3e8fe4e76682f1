// KHR_materials_variants on small files: a variant gives its mapped primitives their materials
// (by name or index, the UV sets and tangents a variant's material needs included), no variant
// keeps each primitive's own, and bad mappings or unknown variants are refused naming the JSON
// pointer or the known variants.
#include <gtest/gtest.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// One triangle whose own material is "plain" (0); variants "red" (1) and "textured" (2) map it
// to materials 1 and 2, the last sampling a texture on TEXCOORD_0.
gltf_builder variant_triangle() {
  gltf_builder b;
  b.add_material({{"name", "plain"}});
  b.add_material({{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}});
  b.doc["images"] = {{{"uri", std::string("data:image/png;base64,") + png_2x2_base64}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.add_material({{"name", "textured"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  const int mesh = b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, 0, {}, {{0, 0}, {1, 0}, {0, 1}});
  b.doc["meshes"][mesh]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
      {{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}};
  b.doc["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}}, {{"name", "textured"}}};
  b.doc["extensionsUsed"].push_back("KHR_materials_variants");
  b.add_node({{"mesh", mesh}});
  return b;
}

scene load_variant(const gltf_builder& b, const temp_folder& dir, const std::string& variant) {
  gltf_load_options options;
  options.variant = variant;
  return load_gltf(b.write(dir.file("variants.gltf")), options);
}

const material& placed_material(const scene& s) { return s.materials.at(s.instances.at(0).material); }

TEST(GltfVariants, AVariantGivesItsMaterialAndNoneKeepsThePrimitivesOwn) {
  temp_folder dir;
  const gltf_builder b = variant_triangle();
  EXPECT_EQ(placed_material(load_variant(b, dir, "")).name, "plain");
  EXPECT_EQ(placed_material(load_variant(b, dir, "red")).name, "red");
  EXPECT_EQ(placed_material(load_variant(b, dir, "0")).name, "red");  // by index
  const scene textured = load_variant(b, dir, "textured");
  EXPECT_EQ(placed_material(textured).name, "textured");
  EXPECT_TRUE(placed_material(textured).base_color_texture.present());
  // The variant's material samples TEXCOORD_0, so the mesh keeps it (the plain one would not).
  EXPECT_EQ(textured.meshes.at(0).texcoords0.size(), 3u);
  EXPECT_TRUE(load_variant(b, dir, "").meshes.at(0).texcoords0.empty());
  EXPECT_EQ(gltf_material_variants(dir.file("variants.gltf")), (std::vector<std::string>{"red", "textured"}));
}

TEST(GltfVariants, UnknownVariantsAndBadMappingsAreRefused) {
  temp_folder dir;
  EXPECT_EQ(error_of([&] { load_variant(variant_triangle(), dir, "blue"); }),
            dir.file("variants.gltf") + ": --variant: no variant 'blue' (variants: 0 'red', 1 'textured')");
  gltf_builder plain;
  plain.add_node({{"mesh", plain.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})}});
  EXPECT_EQ(error_of([&] { load_variant(plain, dir, "red"); }),
            dir.file("variants.gltf") + ": --variant: the file has no KHR_materials_variants variants");
  const std::string mapping = "/meshes/0/primitives/0/extensions/KHR_materials_variants/mappings/1";
  gltf_builder bad_material = variant_triangle();
  bad_material
      .doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][1]["material"] =
      9;
  EXPECT_EQ(error_of([&] { load_variant(bad_material, dir, ""); }),
            dir.file("variants.gltf") + ": " + mapping +
                "/material: /materials/9 does not exist (file has 3 materials)");
  gltf_builder bad_variant = variant_triangle();
  bad_variant.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][1]
                 ["variants"] = {5};
  EXPECT_EQ(
      error_of([&] { load_variant(bad_variant, dir, "red"); }),
      dir.file("variants.gltf") + ": " + mapping +
          "/variants/0: /extensions/KHR_materials_variants/variants/5 does not exist (file has 2 variants)");
  // tinygltf keeps integers in an int, where 2^32 + 1 reads as 1: such indices chose the
  // "textured" variant or material 1 until they were checked on the JSON itself.
  gltf_builder wide_variant = variant_triangle();
  wide_variant.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][0]
                  ["variants"] = {(uint64_t(1) << 32) + 1};
  EXPECT_EQ(
      error_of([&] { load_variant(wide_variant, dir, "textured"); }),
      dir.file("variants.gltf") + ": " +
          "/meshes/0/primitives/0/extensions/KHR_materials_variants/mappings/0/variants/0: "
          "/extensions/KHR_materials_variants/variants/4294967297 does not exist (file has 2 variants)");
  gltf_builder wide_material = variant_triangle();
  wide_material
      .doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][0]["material"] =
      (uint64_t(1) << 32) + 1;
  EXPECT_EQ(error_of([&] { load_variant(wide_material, dir, "red"); }),
            dir.file("variants.gltf") + ": " + mapping.substr(0, mapping.size() - 1) +
                "0/material: /materials/4294967297 does not exist (file has 3 materials)");
  gltf_builder unnamed = variant_triangle();
  unnamed.doc["extensions"]["KHR_materials_variants"]["variants"][1] = {{"name", 3}};
  EXPECT_EQ(error_of([&] { load_variant(unnamed, dir, ""); }),
            dir.file("variants.gltf") +
                ": /extensions/KHR_materials_variants/variants/1/name: a variant needs a string name");
}

}  // namespace
}  // namespace kiln
