// The lobe extensions' members as the loader reads them (KHR_materials_clearcoat, _sheen,
// _iridescence, _anisotropy, _diffuse_transmission, _dispersion): every factor and texture lands in
// the material, out-of-range values are refused naming their JSON pointer, and materials that
// read a tangent frame get one without a normal texture.
#include <gtest/gtest.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;
using nlohmann::json;

// A quad with normals and TEXCOORD_0 wearing `material`, with one 1×1 PNG texture.
gltf_builder lobe_quad(const json& material) {
  gltf_builder b;
  b.doc["images"] = {{{"uri", "data:image/png;base64," + std::string(png_2x2_base64)}}};
  b.doc["textures"] = {{{"source", 0}}};
  const int m = b.add_material(material);
  const int mesh = b.add_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3}, m,
                              {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  b.set_scene({b.add_node({{"mesh", mesh}})});
  return b;
}

json texture(int texcoord = 0) { return {{"index", 0}, {"texCoord", texcoord}}; }

TEST(GltfMaterialLobes, EveryFactorAndTextureReachesTheMaterial) {
  temp_folder dir;
  const json material = {
      {"extensions",
       {{"KHR_materials_clearcoat",
         {{"clearcoatFactor", 0.9},
          {"clearcoatTexture", texture()},
          {"clearcoatRoughnessFactor", 0.3},
          {"clearcoatRoughnessTexture", texture()},
          {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
        {"KHR_materials_sheen",
         {{"sheenColorFactor", {0.5, 0.25, 1.0}},
          {"sheenColorTexture", texture()},
          {"sheenRoughnessFactor", 0.4},
          {"sheenRoughnessTexture", texture()}}},
        {"KHR_materials_iridescence",
         {{"iridescenceFactor", 0.7},
          {"iridescenceTexture", texture()},
          {"iridescenceIor", 1.8},
          {"iridescenceThicknessMinimum", 150.0},
          {"iridescenceThicknessMaximum", 650.0},
          {"iridescenceThicknessTexture", texture()}}},
        {"KHR_materials_anisotropy",
         {{"anisotropyStrength", 0.6}, {"anisotropyRotation", 1.25}, {"anisotropyTexture", texture()}}},
        {"KHR_materials_diffuse_transmission",
         {{"diffuseTransmissionFactor", 0.35},
          {"diffuseTransmissionTexture", texture()},
          {"diffuseTransmissionColorFactor", {0.2, 0.4, 0.6}},
          {"diffuseTransmissionColorTexture", texture()}}},
        {"KHR_materials_dispersion", {{"dispersion", 0.5}}}}}};
  const scene s = load_gltf(lobe_quad(material).write(dir.file("lobes.gltf")));
  ASSERT_EQ(s.materials.size(), 1u);
  const kiln::material& m = s.materials[0];
  EXPECT_FLOAT_EQ(m.clearcoat_factor, 0.9f);
  EXPECT_FLOAT_EQ(m.clearcoat_roughness_factor, 0.3f);
  EXPECT_FLOAT_EQ(m.clearcoat_normal_texture.scale, 0.5f);
  EXPECT_EQ(m.sheen_color_factor, vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(m.sheen_roughness_factor, 0.4f);
  EXPECT_FLOAT_EQ(m.iridescence_factor, 0.7f);
  EXPECT_FLOAT_EQ(m.iridescence_ior, 1.8f);
  EXPECT_FLOAT_EQ(m.iridescence_thickness_minimum, 150.0f);
  EXPECT_FLOAT_EQ(m.iridescence_thickness_maximum, 650.0f);
  EXPECT_FLOAT_EQ(m.anisotropy_strength, 0.6f);
  EXPECT_FLOAT_EQ(m.anisotropy_rotation, 1.25f);
  EXPECT_FLOAT_EQ(m.diffuse_transmission_factor, 0.35f);
  EXPECT_EQ(m.diffuse_transmission_color_factor, vec3(0.2f, 0.4f, 0.6f));
  EXPECT_FLOAT_EQ(m.dispersion, 0.5f);
  for (const texture_ref* t :
       {&m.clearcoat_texture, &m.clearcoat_roughness_texture, &m.clearcoat_normal_texture,
        &m.sheen_color_texture, &m.sheen_roughness_texture, &m.iridescence_texture,
        &m.iridescence_thickness_texture, &m.anisotropy_texture, &m.diffuse_transmission_texture,
        &m.diffuse_transmission_color_texture})
    EXPECT_TRUE(t->present());
  EXPECT_TRUE(m.has_lobe_extensions());
  EXPECT_TRUE(s.stats.warnings.empty()) << s.stats.warnings.front();
}

TEST(GltfMaterialLobes, OutOfRangeMembersAreRefusedNamingTheirPointer) {
  const struct {
    const char* extension;
    json body;
    const char* pointer;
  } cases[] = {
      {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}, "KHR_materials_clearcoat/clearcoatFactor"},
      {"KHR_materials_clearcoat",
       {{"clearcoatRoughnessFactor", -0.1}},
       "KHR_materials_clearcoat/clearcoatRoughnessFactor"},
      {"KHR_materials_clearcoat",
       {{"clearcoatNormalTexture", {{"index", 7}}}},
       "KHR_materials_clearcoat/clearcoatNormalTexture/index"},
      {"KHR_materials_sheen", {{"sheenColorFactor", {1, -1, 0}}}, "KHR_materials_sheen/sheenColorFactor"},
      {"KHR_materials_sheen",
       {{"sheenRoughnessFactor", "rough"}},
       "KHR_materials_sheen/sheenRoughnessFactor"},
      {"KHR_materials_iridescence", {{"iridescenceIor", 0.5}}, "KHR_materials_iridescence/iridescenceIor"},
      {"KHR_materials_iridescence",
       {{"iridescenceThicknessMaximum", -3}},
       "KHR_materials_iridescence/iridescenceThicknessMaximum"},
      {"KHR_materials_anisotropy",
       {{"anisotropyStrength", 2}},
       "KHR_materials_anisotropy/anisotropyStrength"},
      {"KHR_materials_diffuse_transmission",
       {{"diffuseTransmissionFactor", 1.01}},
       "KHR_materials_diffuse_transmission/diffuseTransmissionFactor"},
      {"KHR_materials_dispersion", {{"dispersion", -1}}, "KHR_materials_dispersion/dispersion"},
  };
  for (const auto& c : cases) {
    temp_folder dir;
    const std::string path = lobe_quad({{"extensions", {{c.extension, c.body}}}}).write(dir.file("bad.gltf"));
    const std::string message = error_of([&] { load_gltf(path); });
    EXPECT_NE(message.find(std::string("/materials/0/extensions/") + c.pointer), std::string::npos)
        << message;
    EXPECT_EQ(message.rfind(path, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(GltfMaterialLobes, AnisotropyAndTheCoatNormalMapGetATangentFrameWithoutANormalTexture) {
  for (const json& ext : {json{{"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}}}},
                          json{{"KHR_materials_clearcoat",
                                {{"clearcoatFactor", 1.0}, {"clearcoatNormalTexture", {{"index", 0}}}}}}}) {
    temp_folder dir;
    const scene s = load_gltf(lobe_quad({{"extensions", ext}}).write(dir.file("frame.gltf")));
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].tangents.size(), 4u) << ext.dump();
    // The quad's u runs along +x: the generated tangent is +x. Its v runs along +y, against
    // glTF's downward image v, so the frame is mirrored (w = -1).
    EXPECT_NEAR(s.meshes[0].tangents[0].x, 1.0f, 1e-6f);
    EXPECT_EQ(s.meshes[0].tangents[0].w, -1.0f);
  }
  temp_folder dir;
  const scene plain =
      load_gltf(lobe_quad({{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 1, 1}}}}}}})
                    .write(dir.file("plain.gltf")));
  EXPECT_TRUE(plain.meshes[0].tangents.empty());  // sheen reads no tangent frame
}

}  // namespace
}  // namespace kiln
