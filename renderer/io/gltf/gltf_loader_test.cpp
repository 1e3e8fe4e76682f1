// Loader tests on small glTF files the tests write themselves: geometry reading, topology
// conversion, hierarchy flattening, instancing, materials, textures, lights and cameras.
#include "io/gltf/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

constexpr double tol = 1e-12;

void expect_vec3(const vec3& v, float x, float y, float z) {
  EXPECT_FLOAT_EQ(v.x, x);
  EXPECT_FLOAT_EQ(v.y, y);
  EXPECT_FLOAT_EQ(v.z, z);
}

// z of the geometric normal of triangle t, from the mesh's own positions and winding.
float winding_z(const mesh& m, size_t t) {
  const vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
             c = m.positions[m.indices[3 * t + 2]];
  return glm::cross(b - a, c - a).z;
}

TEST(GltfLoader, ReadsPositionsIndicesAndNormalizesNormals) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 3, 0});
  const int nrm = b.add_data(std::vector<float>{0, 0, 2, 0, 0, 5, 0, 0, 1, 0, 0, 0.5f}, k_float, "VEC3", 3);
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, k_ushort, "SCALAR", 1);
  const int mesh_index = b.add_mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}});
  b.set_scene({b.add_node({{"mesh", mesh_index}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));

  ASSERT_EQ(s.meshes.size(), 1u);
  const mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 4u);
  expect_vec3(m.positions[2], 2, 3, 0);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(m.normals.size(), 4u);
  for (const vec3& n : m.normals) expect_vec3(n, 0, 0, 1);
  EXPECT_TRUE(m.texcoords0.empty());  // no material samples TEXCOORD_0
  EXPECT_DOUBLE_EQ(m.bounds.lower.x, 0.0);
  EXPECT_DOUBLE_EQ(m.bounds.upper.x, 2.0);
  EXPECT_DOUBLE_EQ(m.bounds.upper.y, 3.0);
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.source, b.write(dir.file("scene.gltf")));
}

TEST(GltfLoader, ReadsEveryIndexTypeAndNonIndexed) {
  const std::vector<uint32_t> expected = {0, 1, 2, 2, 1, 3};
  for (int kind = 0; kind < 4; ++kind) {
    SCOPED_TRACE(kind);
    temp_folder dir;
    gltf_builder b;
    const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    json prim = {{"attributes", {{"POSITION", pos}}}};
    if (kind == 0) prim["indices"] = b.add_data(std::vector<uint8_t>{0, 1, 2, 2, 1, 3}, k_ubyte, "SCALAR", 1);
    if (kind == 1)
      prim["indices"] = b.add_data(std::vector<uint16_t>{0, 1, 2, 2, 1, 3}, k_ushort, "SCALAR", 1);
    if (kind == 2) prim["indices"] = b.add_data(std::vector<uint32_t>{0, 1, 2, 2, 1, 3}, k_uint, "SCALAR", 1);
    if (kind == 3) {  // non-indexed: six vertices, each triangle listed in full
      b.doc["accessors"].clear();
      b.doc["bufferViews"].clear();
      b.bin.clear();
      prim["attributes"]["POSITION"] =
          b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0});
    }
    b.set_scene({b.add_node({{"mesh", b.add_mesh(prim)}})});
    const scene s = load_gltf(b.write(dir.file("scene.gltf")));
    ASSERT_EQ(s.meshes.size(), 1u);
    if (kind == 3)
      EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    else
      EXPECT_EQ(s.meshes[0].indices, expected);
    EXPECT_EQ(s.meshes[0].triangle_count(), 2u);
  }
}

TEST(GltfLoader, LoadsGlbAndExternalBin) {
  temp_folder dir;
  const gltf_builder b = single_triangle();
  const std::string glb = dir.file("tri.glb");
  write_bytes(glb, b.glb_bytes());
  EXPECT_EQ(load_gltf(glb).meshes.at(0).triangle_count(), 1u);
  const std::string external = b.write_external(dir.file("tri.gltf"), "tri data.bin");
  EXPECT_EQ(load_gltf(external).meshes.at(0).triangle_count(), 1u);
}

TEST(GltfLoader, ConvertsTriangleStripWithAlternatingWinding) {
  temp_folder dir;
  gltf_builder b;
  // A zig-zag strip along +x in the z = 0 plane: every triangle must face +z.
  const int pos = b.add_positions({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0});
  const int mesh_index = b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 5}});
  b.set_scene({b.add_node({{"mesh", mesh_index}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const mesh& m = s.meshes.at(0);
  ASSERT_EQ(m.triangle_count(), 3u);
  // glTF: triangle i is (v_i, v_{i+1+i%2}, v_{i+2-i%2}).
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
  for (size_t t = 0; t < 3; ++t)
    EXPECT_LT(winding_z(m, t), 0.0f) << t;  // this strip winds clockwise seen from +z
}

TEST(GltfLoader, ConvertsTriangleFan) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0});
  const int mesh_index = b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 6}});
  b.set_scene({b.add_node({{"mesh", mesh_index}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const mesh& m = s.meshes.at(0);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  for (size_t t = 0; t < 3; ++t) EXPECT_GT(winding_z(m, t), 0.0f) << t;
}

TEST(GltfLoader, FlattensThreeLevelHierarchyWithNegativeScale) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  const int mesh_index = 0;
  b.doc["nodes"].clear();
  const double h = std::sqrt(0.5);
  // root: translate (1,2,3); child: rotate 90 degrees about +z; grandchild: scale (2,1,-1).
  b.add_node({{"translation", {1, 2, 3}}, {"children", {1}}});
  b.add_node({{"rotation", {0, 0, h, h}}, {"children", {2}}});
  b.add_node({{"scale", {2, 1, -1}}, {"mesh", mesh_index}});
  b.set_scene({0});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.instances.size(), 1u);
  const instance& inst = s.instances[0];
  EXPECT_EQ(inst.node, 2u);
  const dmat4 expected(dvec4(0, 2, 0, 0), dvec4(-1, 0, 0, 0), dvec4(0, 0, -1, 0), dvec4(1, 2, 3, 1));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(inst.world_from_object[c][r], expected[c][r], tol) << c << "," << r;
  const dvec3 p = transform_point(inst.world_from_object, dvec3(1, 0, 0));
  EXPECT_NEAR(p.x, 1.0, tol);
  EXPECT_NEAR(p.y, 4.0, tol);
  EXPECT_NEAR(p.z, 3.0, tol);
  // The mirror flips the object's +z normal to world -z; the inverse is consistent.
  const dvec3 n = inst.world_from_object_normal * dvec3(0, 0, 1);
  EXPECT_NEAR(n.x, 0.0, tol);
  EXPECT_NEAR(n.y, 0.0, tol);
  EXPECT_NEAR(n.z, -1.0, tol);
  const dmat4 identity = inst.object_from_world * inst.world_from_object;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(identity[c][r], c == r ? 1.0 : 0.0, tol);
  // Winding is kept as authored; mirroring is the normal matrix's job.
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(GltfLoader, MatrixNodeIsColumnMajor) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const dvec3 p = transform_point(s.instances.at(0).world_from_object, dvec3(0));
  EXPECT_EQ(p, dvec3(5, 6, 7));
}

TEST(GltfLoader, MeshUsedByTwoNodesIsStoredOnce) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["nodes"].clear();
  b.add_node({{"mesh", 0}, {"translation", {-1, 0, 0}}});
  b.add_node({{"mesh", 0}, {"translation", {4, 0, 0}}});
  b.set_scene({0, 1});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  EXPECT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].shape, 0u);
  EXPECT_EQ(s.instances[1].shape, 0u);
  EXPECT_DOUBLE_EQ(s.instances[0].world_from_object[3].x, -1.0);
  EXPECT_DOUBLE_EQ(s.instances[1].world_from_object[3].x, 4.0);
  // No material on the primitive: one default material, appended once.
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.instances[0].material, 0u);
  EXPECT_EQ(s.materials[0].base_color_factor, vec4(1.0f));
  EXPECT_FLOAT_EQ(s.materials[0].metallic_factor, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[0].roughness_factor, 1.0f);
}

TEST(GltfLoader, DropsAndCountsDegenerateTriangles) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0});
  // good, repeated index, collinear (zero area)
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2, 0, 0, 1, 0, 1, 3}, k_ushort, "SCALAR", 1);
  const int mesh_index = b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.set_scene({b.add_node({{"mesh", mesh_index}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 2u);
  EXPECT_DOUBLE_EQ(s.meshes[0].bounds.upper.x, 1.0);  // vertex 3 is used by no kept triangle
}

TEST(GltfLoader, AllDegenerateMeshGetsNoInstance) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 2, 0, 0});
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}})}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  EXPECT_TRUE(s.instances.empty());
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 1u);
  EXPECT_FALSE(s.materials.empty());
}

TEST(GltfLoader, SkipsPointsAndLinesWithOneWarning) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  json mesh_json = {{"primitives",
                     {{{"attributes", {{"POSITION", pos}}}, {"mode", 0}},
                      {{"attributes", {{"POSITION", pos}}}, {"mode", 1}},
                      {{"attributes", {{"POSITION", pos}}}, {"mode", 3}},
                      {{"attributes", {{"POSITION", pos}}}, {"mode", 4}}}}};
  b.doc["meshes"].push_back(mesh_json);
  b.set_scene({b.add_node({{"mesh", 0}}), b.add_node({{"mesh", 0}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  EXPECT_EQ(s.stats.non_triangle_primitives_skipped, 3u);  // per unique primitive, not per placement
  size_t mentions = 0;
  for (const std::string& w : s.stats.warnings) mentions += w.find("line") != std::string::npos;
  EXPECT_EQ(mentions, 1u);
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.instances.size(), 2u);
}

TEST(GltfLoader, AppliesSparseAccessor) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 9, 9, 9});
  const std::vector<uint16_t> sparse_indices = {1, 3};
  const std::vector<float> sparse_values = {5, 0, 0, 5, 5, 0};
  const int iv = b.add_view(sparse_indices.data(), 4);
  const int vv = b.add_view(sparse_values.data(), 24);
  b.doc["accessors"][pos]["sparse"] = {{"count", 2},
                                       {"indices", {{"bufferView", iv}, {"componentType", k_ushort}}},
                                       {"values", {{"bufferView", vv}}}};
  const int idx = b.add_data(std::vector<uint8_t>{0, 1, 3}, k_ubyte, "SCALAR", 1);
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const mesh& m = s.meshes.at(0);
  expect_vec3(m.positions[0], 0, 0, 0);
  expect_vec3(m.positions[1], 5, 0, 0);
  expect_vec3(m.positions[2], 0, 1, 0);
  expect_vec3(m.positions[3], 5, 5, 0);
}

TEST(GltfLoader, SparseAccessorWithoutBufferViewStartsFromZeros) {
  temp_folder dir;
  gltf_builder b;
  const std::vector<uint8_t> sparse_indices = {1, 2};
  const std::vector<float> sparse_values = {1, 0, 0, 0, 1, 0};
  const int iv = b.add_view(sparse_indices.data(), 2);
  const int vv = b.add_view(sparse_values.data(), 24);
  const int pos = b.add_accessor(-1, k_float, 3, "VEC3");
  b.doc["accessors"][pos]["sparse"] = {{"count", 2},
                                       {"indices", {{"bufferView", iv}, {"componentType", k_ubyte}}},
                                       {"values", {{"bufferView", vv}}}};
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}})}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const mesh& m = s.meshes.at(0);
  expect_vec3(m.positions[0], 0, 0, 0);
  expect_vec3(m.positions[1], 1, 0, 0);
  expect_vec3(m.positions[2], 0, 1, 0);
}

TEST(GltfLoader, ReadsInterleavedAttributes) {
  temp_folder dir;
  gltf_builder b;
  // position xyz + normal xyz per vertex, stride 24
  const std::vector<float> interleaved = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
  const int view = b.add_view(interleaved.data(), interleaved.size() * 4, 24);
  const int pos = b.add_accessor(view, k_float, 3, "VEC3");
  const int nrm = b.add_accessor(view, k_float, 3, "VEC3", 12);
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}})}})});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const mesh& m = s.meshes.at(0);
  expect_vec3(m.positions[2], 0, 1, 0);
  expect_vec3(m.normals[1], 0, 0, 1);
}

// A textured quad: material 0 samples the PNG through TEXCOORD_0 with a clamp/nearest sampler.
gltf_builder textured_quad(const std::string& png_base64, int texcoord_component, bool normalized) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int uv = 0;
  if (texcoord_component == k_float)
    uv = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1}, k_float, "VEC2", 2);
  if (texcoord_component == k_ubyte)
    uv = b.add_data(std::vector<uint8_t>{0, 0, 255, 0, 0, 255}, k_ubyte, "VEC2", 2, normalized);
  if (texcoord_component == k_ushort)
    uv = b.add_data(std::vector<uint16_t>{0, 0, 65535, 0, 0, 65535}, k_ushort, "VEC2", 2, normalized);
  b.doc["images"] = json::array({json{{"uri", "data:image/png;base64," + png_base64}},
                                 json{{"uri", "data:image/png;base64,AAAA"}}});  // unused, corrupt
  b.doc["samplers"] = json::array({json{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}});
  b.doc["textures"] = json::array({json{{"source", 0}, {"sampler", 0}}, json{{"source", 1}}});
  b.doc["materials"] = json::array(
      {json{{"name", "unused"}},
       json{{"name", "painted"},
            {"pbrMetallicRoughness",
             {{"baseColorFactor", {0.5, 0.25, 1, 1}},
              {"baseColorTexture", {{"index", 0}}},
              {"metallicFactor", 0.25},
              {"roughnessFactor", 0.75}}},
            {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
            // Occlusion is never decoded (no ambient term): its texture reads the corrupt image.
            {"occlusionTexture", {{"index", 1}, {"strength", 0.3}}},
            {"emissiveFactor", {1, 0.5, 0}},
            {"alphaMode", "MASK"},
            {"alphaCutoff", 0.4},
            {"doubleSided", true},
            {"extensions",
             {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}},
              {"KHR_materials_ior", {{"ior", 1.33}}},
              {"KHR_materials_specular", {{"specularFactor", 0.7}, {"specularColorFactor", {1, 0.5, 0.25}}}},
              {"KHR_materials_transmission",
               {{"transmissionFactor", 0.8}, {"transmissionTexture", {{"index", 0}}}}},
              {"KHR_materials_volume",
               {{"thicknessFactor", 0.1},
                {"attenuationDistance", 2.5},
                {"attenuationColor", {0.9, 0.8, 0.7}}}}}}}});
  const int mesh_index =
      b.add_mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"material", 1}});
  b.set_scene({b.add_node({{"mesh", mesh_index}})});
  return b;
}

TEST(GltfLoader, ConvertsMaterialsTexturesAndOnlyUsedImages) {
  temp_folder dir;
  const scene s = load_gltf(textured_quad(png_2x2_base64, k_float, false).write(dir.file("scene.gltf")));
  ASSERT_EQ(s.materials.size(), 1u);  // only the used material; the corrupt unused image is never decoded
  const material& m = s.materials[0];
  EXPECT_EQ(m.name, "painted");
  EXPECT_EQ(m.base_color_factor, vec4(0.5f, 0.25f, 1.0f, 1.0f));
  EXPECT_FLOAT_EQ(m.metallic_factor, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness_factor, 0.75f);
  EXPECT_EQ(m.emissive_factor, vec3(1.0f, 0.5f, 0.0f));
  EXPECT_FLOAT_EQ(m.emissive_strength, 4.0f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.specular_factor, 0.7f);
  EXPECT_EQ(m.specular_color_factor, vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(m.alpha, alpha_mode::mask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.4f);
  EXPECT_TRUE(m.double_sided);
  EXPECT_EQ(m.base_color_texture.texture, 0);
  EXPECT_EQ(m.normal_texture.texture, 0);
  EXPECT_FLOAT_EQ(m.normal_texture.scale, 0.5f);
  EXPECT_EQ(s.images.size(), 1u);  // the occlusion texture's image is not held
  EXPECT_FALSE(m.emissive_texture.present());
  EXPECT_FALSE(m.metallic_roughness_texture.present());
  EXPECT_FALSE(m.unlit);
  EXPECT_FLOAT_EQ(m.transmission_factor, 0.8f);
  EXPECT_EQ(m.transmission_texture.texture, 0);
  EXPECT_FLOAT_EQ(m.thickness_factor, 0.1f);
  EXPECT_FLOAT_EQ(m.attenuation_distance, 2.5f);
  EXPECT_EQ(m.attenuation_color, vec3(0.9f, 0.8f, 0.7f));

  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].sampling.wrap_s, wrap_mode::clamp_to_edge);
  EXPECT_EQ(s.textures[0].sampling.wrap_t, wrap_mode::mirrored_repeat);
  EXPECT_EQ(s.textures[0].sampling.filter, filter_mode::nearest);
  // No minFilter: trilinear mip-mapping.
  EXPECT_EQ(s.textures[0].sampling.min_filter, filter_mode::linear);
  EXPECT_EQ(s.textures[0].sampling.mipmap, mip_mode::linear);
  ASSERT_EQ(s.images.size(), 1u);
  const image& img = s.images[0];
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.height, 2);
  ASSERT_EQ(img.texels8.size(), 16u);
  EXPECT_TRUE(img.texels32.empty());
  // Row 0 is the top row of the PNG: red, green; then blue, white with alpha 128 (not premultiplied).
  EXPECT_EQ(std::vector<uint8_t>(img.texels8.begin(), img.texels8.begin() + 8),
            (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255}));
  EXPECT_EQ(std::vector<uint8_t>(img.texels8.begin() + 8, img.texels8.end()),
            (std::vector<uint8_t>{0, 0, 255, 255, 255, 255, 255, 128}));

  ASSERT_EQ(s.meshes.at(0).texcoords0.size(), 3u);
  EXPECT_EQ(s.meshes[0].texcoords0[1], vec2(1, 0));
}

TEST(GltfLoader, ReadsNormalizedIntegerTexcoords) {
  for (int component : {k_ubyte, k_ushort}) {
    temp_folder dir;
    const scene s = load_gltf(textured_quad(png_2x2_base64, component, true).write(dir.file("scene.gltf")));
    const auto& uv = s.meshes.at(0).texcoords0;
    ASSERT_EQ(uv.size(), 3u);
    EXPECT_FLOAT_EQ(uv[1].x, 1.0f);
    EXPECT_FLOAT_EQ(uv[2].y, 1.0f);
    EXPECT_FLOAT_EQ(uv[0].x, 0.0f);
  }
}

TEST(GltfLoader, DecodesSixteenBitImagesAsFloat) {
  temp_folder dir;
  const scene s = load_gltf(textured_quad(png_16bit_base64, k_float, false).write(dir.file("scene.gltf")));
  ASSERT_EQ(s.images.size(), 1u);
  const image& img = s.images[0];
  EXPECT_TRUE(img.texels8.empty());
  ASSERT_EQ(img.texels32.size(), 4u);
  EXPECT_FLOAT_EQ(img.texels32[0], 1.0f);
  EXPECT_NEAR(img.texels32[1], 32768.0f / 65535.0f, 1e-6);
  EXPECT_FLOAT_EQ(img.texels32[2], 0.0f);
  EXPECT_FLOAT_EQ(img.texels32[3], 1.0f);
}

// Each glTF minFilter splits into a texel filter and a mip mode; an unknown one is refused.
TEST(GltfLoader, ReadsEveryMinFilter) {
  struct expected {
    int gl;
    filter_mode filter;
    mip_mode mipmap;
  };
  const expected cases[] = {
      {9728, filter_mode::nearest, mip_mode::none},    {9729, filter_mode::linear, mip_mode::none},
      {9984, filter_mode::nearest, mip_mode::nearest}, {9985, filter_mode::linear, mip_mode::nearest},
      {9986, filter_mode::nearest, mip_mode::linear},  {9987, filter_mode::linear, mip_mode::linear}};
  for (const expected& e : cases) {
    temp_folder dir;
    gltf_builder b = textured_quad(png_2x2_base64, k_float, false);
    b.doc["samplers"][0]["minFilter"] = e.gl;
    const scene s = load_gltf(b.write(dir.file("scene.gltf")));
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].sampling.min_filter, e.filter) << e.gl;
    EXPECT_EQ(s.textures[0].sampling.mipmap, e.mipmap) << e.gl;
    EXPECT_EQ(s.textures[0].sampling.filter, filter_mode::nearest) << e.gl;  // magFilter untouched
  }
  temp_folder dir;
  gltf_builder b = textured_quad(png_2x2_base64, k_float, false);
  b.doc["samplers"][0]["minFilter"] = 9730;
  const std::string path = b.write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("/samplers/0/minFilter"), std::string::npos) << message;
}

TEST(GltfLoader, CorruptImageUsedByMaterialNamesTheImage) {
  temp_folder dir;
  gltf_builder b = textured_quad(png_2x2_base64, k_float, false);
  b.doc["textures"][0]["source"] = 1;
  const std::string path = b.write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("/images/1"), std::string::npos) << message;
}

TEST(GltfLoader, TextureWithoutSourceIsAbsentWithWarning) {
  temp_folder dir;
  gltf_builder b = textured_quad(png_2x2_base64, k_float, false);
  b.doc["textures"][0].erase("source");
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  EXPECT_FALSE(s.materials.at(0).base_color_texture.present());
  EXPECT_TRUE(s.images.empty());
  bool warned = false;
  for (const std::string& w : s.stats.warnings) warned |= w.find("/textures/0") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(GltfLoader, PlacesLightsWithNodeTransforms) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  const double h = std::sqrt(0.5);
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
      {json{{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 20}, {"range", 7}},
       json{{"type", "spot"}, {"intensity", 3}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}},
       json{{"type", "directional"}, {"intensity", 2}}});
  b.add_node({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  // Rotating -90 degrees about x turns the local -z axis into world -y.
  b.add_node({{"translation", {0, 5, 0}},
              {"rotation", {-h, 0, 0, h}},
              {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  b.add_node({{"scale", {3, 3, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  b.set_scene({0, 1, 2, 3});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].kind, light_kind::point);
  EXPECT_EQ(s.lights[0].position, dvec3(1, 2, 3));
  EXPECT_EQ(s.lights[0].color, vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 20.0f);
  EXPECT_FLOAT_EQ(s.lights[0].range, 7.0f);
  EXPECT_EQ(s.lights[1].kind, light_kind::spot);
  EXPECT_NEAR(s.lights[1].position.y, 5.0, tol);
  EXPECT_NEAR(s.lights[1].direction.x, 0.0f, 1e-6);
  EXPECT_NEAR(s.lights[1].direction.y, -1.0f, 1e-6);
  EXPECT_NEAR(s.lights[1].direction.z, 0.0f, 1e-6);
  EXPECT_FLOAT_EQ(s.lights[1].inner_cone_angle, 0.1f);
  EXPECT_FLOAT_EQ(s.lights[1].outer_cone_angle, 0.5f);
  EXPECT_EQ(s.lights[2].kind, light_kind::directional);
  EXPECT_NEAR(glm::length(s.lights[2].direction), 1.0f, 1e-6);  // scale does not leak into direction
  EXPECT_NEAR(s.lights[2].direction.z, -1.0f, 1e-6);
}

TEST(GltfLoader, PlacesCamerasWithoutScale) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["cameras"] = json::array(
      {json{{"type", "perspective"}, {"name", "main"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}},
       json{{"type", "orthographic"},
            {"orthographic", {{"xmag", 2}, {"ymag", 1.5}, {"znear", 0.0}, {"zfar", 10}}}}});
  b.add_node({{"camera", 0}, {"translation", {0, 0, 10}}, {"scale", {2, 3, 4}}});
  b.add_node({{"camera", 1}, {"name", "side"}, {"translation", {4, 0, 0}}});
  b.set_scene({0, 1, 2});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.cameras.size(), 2u);
  const camera& persp = s.cameras[0];
  EXPECT_EQ(persp.name, "main");
  EXPECT_EQ(persp.kind, projection::perspective);
  EXPECT_FLOAT_EQ(persp.yfov, 0.6f);
  EXPECT_FLOAT_EQ(persp.aspect_ratio, 0.0f);
  EXPECT_FLOAT_EQ(persp.znear, 0.1f);
  const dmat4 expected(dvec4(1, 0, 0, 0), dvec4(0, 1, 0, 0), dvec4(0, 0, 1, 0), dvec4(0, 0, 10, 1));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(persp.world_from_camera[c][r], expected[c][r], tol);
  const camera& ortho = s.cameras[1];
  EXPECT_EQ(ortho.name, "side");
  EXPECT_EQ(ortho.kind, projection::orthographic);
  EXPECT_FLOAT_EQ(ortho.xmag, 2.0f);
  EXPECT_FLOAT_EQ(ortho.ymag, 1.5f);
}

TEST(GltfLoader, ChoosesSceneFromOptionsOrDefault) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.add_node({{"mesh", 0}});
  b.add_node({{"mesh", 0}});
  b.doc["scenes"] = json::array({json{{"nodes", {0}}}, json{{"nodes", {1, 2}}}});
  b.doc["scene"] = 1;
  const std::string path = b.write(dir.file("scene.gltf"));
  EXPECT_EQ(load_gltf(path).instances.size(), 2u);
  gltf_load_options first;
  first.scene_index = 0;
  EXPECT_EQ(load_gltf(path, first).instances.size(), 1u);
  gltf_load_options missing;
  missing.scene_index = 5;
  const std::string message = error_of([&] { load_gltf(path, missing); });
  EXPECT_NE(message.find("/scenes/5 does not exist (file has 2 scenes)"), std::string::npos) << message;
}

TEST(GltfLoader, WarnsAboutUnsupportedUsedExtensions) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness", "KHR_lights_punctual",
                             "EXT_lights_image_based"};
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  // One line names every unsupported optional extension, and only those.
  ASSERT_EQ(s.stats.warnings.size(), 1u);
  EXPECT_EQ(
      s.stats.warnings[0],
      "extensions KHR_materials_pbrSpecularGlossiness, EXT_lights_image_based are not supported; they are "
      "ignored");
  b.doc["extensionsUsed"] = {"EXT_lights_image_based"};
  EXPECT_EQ(load_gltf(b.write(dir.file("scene.gltf"))).stats.warnings,
            std::vector<std::string>{"extension EXT_lights_image_based is not supported; it is ignored"});
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

TEST(GltfLoader, ReadsTexcoord1ColorsAndTextureTransform) {
  temp_folder dir;
  gltf_builder b = textured_quad(png_2x2_base64, k_float, false);
  json& prim = b.doc["meshes"][0]["primitives"][0];
  prim["attributes"]["TEXCOORD_1"] =
      b.add_data(std::vector<float>{0.5f, 0.5f, 1, 0.5f, 0.5f, 1}, k_float, "VEC2", 2);
  prim["attributes"]["COLOR_0"] = b.add_data(
      std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0}, k_ubyte, "VEC4", 4, true);
  // The base colour texture moves to TEXCOORD_1 through KHR_texture_transform's texCoord.
  b.doc["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {
      {"offset", {0.25, -0.5}}, {"rotation", 0.5}, {"scale", {2, 3}}, {"texCoord", 1}};
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  const material& m = s.materials.at(0);
  EXPECT_EQ(m.base_color_texture.texcoord, 1u);
  EXPECT_EQ(m.base_color_texture.offset, vec2(0.25f, -0.5f));
  EXPECT_FLOAT_EQ(m.base_color_texture.rotation, 0.5f);
  EXPECT_EQ(m.base_color_texture.uv_scale, vec2(2.0f, 3.0f));
  const mesh& mesh0 = s.meshes.at(0);
  ASSERT_EQ(mesh0.texcoords1.size(), 3u);
  EXPECT_EQ(mesh0.texcoords1[1], vec2(1.0f, 0.5f));
  EXPECT_EQ(mesh0.texcoords0.size(), 3u);  // normal and occlusion textures still read TEXCOORD_0
  ASSERT_EQ(mesh0.colors0.size(), 3u);
  EXPECT_EQ(mesh0.colors0[0], vec4(1, 0, 0, 1));
  EXPECT_NEAR(mesh0.colors0[1].a, 128.0f / 255.0f, 1e-6f);

  prim["attributes"]["COLOR_0"] = b.add_data(std::vector<float>{1, 0, 0, 1}, k_float, "VEC2", 2);
  const std::string message = error_of([&] { load_gltf(b.write(dir.file("scene.gltf"))); });
  EXPECT_NE(message.find("COLOR_0 must be VEC3/VEC4"), std::string::npos) << message;
}

}  // namespace
}  // namespace kiln

#include "io/gltf/mesh_tangents.h"

namespace kiln {
namespace {

TEST(MeshTangents, FollowUAndTheUpwardImageDirection) {
  // A quad in the xy plane facing +z, u along +x, glTF v growing along -y (image rows downward):
  // the tangent is +x and the bitangent cross(n, t)·w = +y points up the image (w = +1).
  mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, vec3(0, 0, 1));
  m.indices = {0, 1, 2, 0, 2, 3};
  std::vector<vec4> t = generate_tangents(m, {{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  for (const vec4& v : t) {
    EXPECT_NEAR(v.x, 1.0f, 1e-6f);
    EXPECT_NEAR(v.y, 0.0f, 1e-6f);
    EXPECT_EQ(v.w, 1.0f);
  }
  // Mirrored texture (v growing along +y): same tangent, opposite handedness.
  t = generate_tangents(m, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_NEAR(t[0].x, 1.0f, 1e-6f);
  EXPECT_EQ(t[0].w, -1.0f);
}

}  // namespace
}  // namespace kiln
