// Bad-input tests: every kind of broken reference, layout, container or value must be refused
// with one kiln::error whose message names the file, the JSON pointer and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// Writes the builder as .gltf, loads it, and checks the error message holds every fragment.
void expect_error(const gltf_builder& b, const std::vector<std::string>& fragments) {
  temp_folder dir;
  const std::string path = b.write(dir.file("scene.gltf"));
  std::string message;
  try {
    load_gltf(path);
    ADD_FAILURE() << "expected an error containing '" << fragments.at(0) << "'";
    return;
  } catch (const kiln::error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    message = e.what();
  }
  EXPECT_EQ(message.find('\n'), std::string::npos) << "message must be one line: " << message;
  EXPECT_EQ(message.rfind(path, 0), 0u) << "message must start with the file: " << message;
  for (const std::string& f : fragments)
    EXPECT_NE(message.find(f), std::string::npos) << "'" << f << "' not in: " << message;
}

TEST(GltfLoaderErrors, AccessorBufferViewOutOfRange) {
  gltf_builder b = single_triangle();
  b.doc["accessors"][0]["bufferView"] = 7;
  expect_error(b, {"/accessors/0/bufferView", "/bufferViews/7 does not exist"});
}

TEST(GltfLoaderErrors, AccessorPastEndOfBufferView) {
  gltf_builder b = single_triangle();
  b.doc["accessors"][0]["count"] = 4;  // 4 * 12 bytes > 36
  expect_error(b, {"/accessors/0", "reads past the end of bufferView 0 (needs 48 bytes, has 36)"});
}

TEST(GltfLoaderErrors, AccessorOffsetPastEndOfBufferView) {
  gltf_builder b = single_triangle();
  b.doc["accessors"][0]["byteOffset"] = 4;
  expect_error(b, {"/accessors/0", "reads past the end of bufferView 0"});
}

TEST(GltfLoaderErrors, AccessorCountOverflowIsCaught) {
  gltf_builder b = single_triangle();
  b.doc["accessors"][0]["count"] = std::numeric_limits<int64_t>::max() / 8;
  expect_error(b, {"/accessors/0/count", "larger than any glTF buffer"});
}

TEST(GltfLoaderErrors, BufferViewPastEndOfBuffer) {
  gltf_builder b = single_triangle();
  b.doc["bufferViews"][1]["byteLength"] = 100;
  expect_error(b, {"/bufferViews/1", "reads past the end of buffer 0"});
}

TEST(GltfLoaderErrors, BufferViewBufferOutOfRange) {
  gltf_builder b = single_triangle();
  b.doc["bufferViews"][0]["buffer"] = 3;
  expect_error(b, {"/bufferViews/0/buffer", "/buffers/3 does not exist"});
}

TEST(GltfLoaderErrors, StrideSmallerThanElement) {
  gltf_builder b = single_triangle();
  b.doc["bufferViews"][0]["byteStride"] = 8;  // a VEC3 FLOAT needs 12
  expect_error(b, {"/accessors/0", "byteStride 8", "smaller than one VEC3 FLOAT element"});
}

TEST(GltfLoaderErrors, StrideLargerThanBufferView) {
  gltf_builder b = single_triangle();
  b.doc["bufferViews"][1]["byteStride"] = 12;  // the index view is 6 bytes long
  expect_error(b, {"/bufferViews/1/byteStride", "larger than byteLength"});
}

TEST(GltfLoaderErrors, MisalignedAccessorOffset) {
  gltf_builder b = single_triangle();
  b.doc["accessors"][0]["byteOffset"] = 2;
  b.doc["accessors"][0]["count"] = 2;
  expect_error(b, {"/accessors/0/byteOffset", "not a multiple of the component size 4"});
}

TEST(GltfLoaderErrors, IndexOutOfRange) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int idx = b.add_data(std::vector<uint32_t>{0, 1, 3}, k_uint, "SCALAR", 1);
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  expect_error(b, {"/meshes/0/primitives/0/indices",
                   "index 3 at position 2 is out of range (POSITION has 3 vertices)"});
}

TEST(GltfLoaderErrors, WrongComponentTypeForPosition) {
  gltf_builder b;
  const int pos = b.add_data(std::vector<uint16_t>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0}, k_ushort, "VEC3", 3);
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}})}})});
  expect_error(
      b, {"/meshes/0/primitives/0/attributes/POSITION", "POSITION must be VEC3 FLOAT", "UNSIGNED_SHORT"});
}

TEST(GltfLoaderErrors, WrongIndexFormat) {
  gltf_builder b = single_triangle();
  b.doc["accessors"][1]["componentType"] = k_short;
  expect_error(b, {"/meshes/0/primitives/0/indices", "indices must be SCALAR"});
}

TEST(GltfLoaderErrors, UnequalAttributeCounts) {
  gltf_builder b = single_triangle();
  const int nrm = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1}, k_float, "VEC3", 3);
  b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = nrm;
  expect_error(b, {"/meshes/0/primitives/0/attributes/NORMAL", "2 elements but POSITION has 3"});
}

TEST(GltfLoaderErrors, NanInPositionData) {
  gltf_builder b;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int pos = b.add_positions({0, 0, 0, 1, nan, 0, 0, 1, 0});
  b.set_scene({b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}})}})});
  expect_error(b, {"/meshes/0/primitives/0/attributes/POSITION", "element 1", "NaN or infinite"});
}

TEST(GltfLoaderErrors, NonFiniteNodeMatrix) {
  // JSON has no NaN literal; a broken exporter writes 1e999 instead, which must not load.
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 12345, 0, 0, 1};
  std::string text = b.finished("data:application/octet-stream;base64," + base64_encode(b.bin)).dump();
  text.replace(text.find("12345"), 5, "1e999");
  const std::string path = dir.file("inf.gltf");
  write_text(path, text);
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("1e999"), std::string::npos) << message;
}

TEST(GltfLoaderErrors, NonFiniteTranslationOnUnusedNode) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.add_node({{"translation", {0, 777, 0}}});
  std::string text = b.finished("data:application/octet-stream;base64," + base64_encode(b.bin)).dump();
  text.replace(text.find("777"), 3, "-1e999");
  const std::string path = dir.file("inf.gltf");
  write_text(path, text);
  EXPECT_NE(error_of([&] { load_gltf(path); }), "");
}

TEST(GltfLoaderErrors, MatrixWithWrongLength) {
  gltf_builder b = single_triangle();
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  expect_error(b, {"/nodes/0/matrix", "12 numbers, expected 16"});
}

TEST(GltfLoaderErrors, WorldTransformOverflow) {
  // Each matrix is finite; their product is not.
  gltf_builder b = single_triangle();
  b.doc["nodes"][0]["matrix"] = {1e300, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  b.add_node({{"matrix", {1e300, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}, {"children", {0}}});
  b.set_scene({1});
  expect_error(b, {"/nodes/0", "world transform overflows to infinity"});
}

// A NaN rotation: JSON has no NaN, so a broken exporter's NaN or 1e999 in the node's rotation is
// refused at that member; a NaN in an animation's rotation keyframes at the sampler's output.
TEST(GltfLoaderErrors, NaNRotationsAreRefusedNamingTheirPointer) {
  for (const char* literal : {"NaN", "1e999"}) {
    temp_folder dir;
    gltf_builder b = single_triangle();
    b.doc["nodes"][0]["rotation"] = {0, 0, 4321, 1};
    std::string text = b.finished("data:application/octet-stream;base64," + base64_encode(b.bin)).dump();
    text.replace(text.find("4321"), 4, literal);
    const std::string path = dir.file("rotation.gltf");
    write_text(path, text);
    const std::string message = error_of([&] { load_gltf(path); });
    EXPECT_EQ(message.rfind(path + ": /nodes/0/rotation", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  gltf_builder b = single_triangle();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int input = b.add_data(std::vector<float>{0, 1}, k_float, "SCALAR", 1);
  const int output = b.add_data(std::vector<float>{0, 0, 0, 1, nan, 0, 0, 1}, k_float, "VEC4", 4);
  b.doc["animations"] = {{{"samplers", {{{"input", input}, {"output", output}}}},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}}}}};
  expect_error(b, {"/animations/0/samplers/0/output", "keyframe value 4 is NaN or infinite"});
}

TEST(GltfLoaderErrors, ZeroQuaternion) {
  gltf_builder b = single_triangle();
  b.doc["nodes"][0]["rotation"] = {0, 0, 0, 0};
  expect_error(b, {"/nodes/0/rotation", "zero length"});
}

TEST(GltfLoaderErrors, IndexOutOfRangeInUnplacedMesh) {
  gltf_builder b = single_triangle();
  b.doc["scenes"][0]["nodes"] = json::array();
  const std::vector<uint16_t> bad = {0, 1, 9};
  const int view = b.add_view(bad.data(), 6);
  b.doc["accessors"][1]["bufferView"] = view;
  expect_error(b, {"/meshes/0/primitives/0/indices", "index 9"});
}

TEST(GltfLoaderErrors, NodeCycle) {
  gltf_builder b = single_triangle();
  b.doc["nodes"].clear();
  b.add_node({{"mesh", 0}});
  b.add_node({{"children", {2}}});
  b.add_node({{"children", {1}}});
  b.set_scene({0});
  expect_error(b, {"/nodes/1", "cycle"});
}

TEST(GltfLoaderErrors, NodeIsItsOwnChild) {
  gltf_builder b = single_triangle();
  b.doc["nodes"][0]["children"] = {0};
  expect_error(b, {"/nodes/0/children/0", "its own child"});
}

TEST(GltfLoaderErrors, NodeWithTwoParents) {
  gltf_builder b = single_triangle();
  b.add_node({{"children", {0}}});
  b.add_node({{"children", {0}}});
  b.set_scene({1, 2});
  expect_error(b, {"/nodes/2/children/0", "already has parent node 1"});
}

TEST(GltfLoaderErrors, SceneListsNonRootNode) {
  gltf_builder b = single_triangle();
  b.add_node({{"children", {0}}});
  b.set_scene({0, 1});
  expect_error(b, {"/scenes/0/nodes/0", "not a root node"});
}

TEST(GltfLoaderErrors, ReferencesOutOfRange) {
  {
    gltf_builder b = single_triangle();
    b.doc["nodes"][0]["mesh"] = 4;
    expect_error(b, {"/nodes/0/mesh", "/meshes/4 does not exist (file has 1 meshes)"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["nodes"][0]["children"] = {9};
    expect_error(b, {"/nodes/0/children/0", "/nodes/9 does not exist"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    expect_error(b, {"/meshes/0/primitives/0/material", "/materials/0 does not exist"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["materials"] = json::array({json{{"emissiveTexture", {{"index", 2}}}}});
    expect_error(b, {"/materials/0/emissiveTexture/index", "/textures/2 does not exist"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["textures"] = json::array({json{{"source", 0}}});
    expect_error(b, {"/textures/0/source", "/images/0 does not exist"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["materials"] =
        json::array({json{{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}}}});
    expect_error(b, {"/materials/0/extensions/KHR_materials_transmission/transmissionFactor", "in [0"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["materials"] = json::array(
        {json{{"extensions", {{"KHR_materials_transmission", {{"transmissionTexture", {{"index", 4}}}}}}}}});
    expect_error(b, {"/materials/0/extensions/KHR_materials_transmission/transmissionTexture/index",
                     "/textures/4 does not exist (file has 0 textures)"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["materials"] =
        json::array({json{{"extensions", {{"KHR_materials_volume", {{"attenuationColor", {1, 0.5}}}}}}}});
    expect_error(b, {"/materials/0/extensions/KHR_materials_volume/attenuationColor", "3 numbers"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["scene"] = 3;
    expect_error(b, {"/scene", "/scenes/3 does not exist (file has 1 scenes)"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    expect_error(b, {"/nodes/0/extensions/KHR_lights_punctual/light", "/lights/0 does not exist"});
  }
}

TEST(GltfLoaderErrors, SparseIndexOutOfRange) {
  gltf_builder b = single_triangle();
  const std::vector<uint8_t> sparse_indices = {5, 0, 0, 0};
  const std::vector<float> sparse_values = {1, 1, 1};
  const int iv = b.add_view(sparse_indices.data(), 1);
  const int vv = b.add_view(sparse_values.data(), 12);
  b.doc["accessors"][0]["sparse"] = {{"count", 1},
                                     {"indices", {{"bufferView", iv}, {"componentType", k_ubyte}}},
                                     {"values", {{"bufferView", vv}}}};
  expect_error(b, {"/accessors/0/sparse/indices", "sparse index 5"});
}

TEST(GltfLoaderErrors, SparseValuesPastEndOfBufferView) {
  gltf_builder b = single_triangle();
  const std::vector<uint8_t> sparse_indices = {0, 1, 0, 0};
  const std::vector<float> sparse_values = {1, 1, 1};
  const int iv = b.add_view(sparse_indices.data(), 2);
  const int vv = b.add_view(sparse_values.data(), 12);
  b.doc["accessors"][0]["sparse"] = {{"count", 2},
                                     {"indices", {{"bufferView", iv}, {"componentType", k_ubyte}}},
                                     {"values", {{"bufferView", vv}}}};
  expect_error(b,
               {"/accessors/0/sparse/values", "reads past the end of bufferView 3 (needs 24 bytes, has 12)"});
}

TEST(GltfLoaderErrors, UnsupportedRequiredExtensionIsNamed) {
  gltf_builder b = single_triangle();
  b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_pbrSpecularGlossiness"};
  b.doc["extensionsRequired"] = {"KHR_lights_punctual", "KHR_materials_pbrSpecularGlossiness"};
  expect_error(b, {"/extensionsRequired/1",
                   "required extension KHR_materials_pbrSpecularGlossiness is not supported"});
}

TEST(GltfLoaderErrors, RequiredBasisuTexturesAreRefusedWithTheReason) {
  gltf_builder b = single_triangle();
  b.doc["extensionsUsed"] = {"KHR_texture_basisu"};
  b.doc["extensionsRequired"] = {"KHR_texture_basisu"};
  expect_error(b,
               {"/extensionsRequired/0",
                "required extension KHR_texture_basisu is not supported: no KTX2/Basis Universal decoder"});
}

// Materials hold floats: a number a double holds but a float does not would shade as infinity
// or NaN (an emissiveStrength of 3.5e38 lost every sample that saw it), so it is refused.
TEST(GltfLoaderErrors, MaterialValuesPastTheLargestFloatAreRefused) {
  const auto with_material = [](const json& material) {
    gltf_builder b = single_triangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["materials"] = json::array({material});
    return b;
  };
  const json strength = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3.5e38}}}};
  expect_error(with_material({{"extensions", strength}}),
               {"/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength",
                "emissiveStrength 3.5e+38 is past the largest float (3.40282e+38)"});
  // Each fits a float, their product does not.
  expect_error(
      with_material({{"emissiveFactor", {0.5, 2, 0}},
                     {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3e38}}}}}}),
      {"/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength",
       "emissiveStrength 3e+38 times emissiveFactor is 6e+38, past the largest float"});
  expect_error(with_material({{"emissiveFactor", {1e39, 0, 0}}}), {"/materials/0/emissiveFactor"});
  expect_error(with_material({{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1e300, 1}}}}}),
               {"/materials/0/pbrMetallicRoughness/baseColorFactor"});
  expect_error(
      with_material({{"extensions", {{"KHR_materials_specular", {{"specularColorFactor", {1, 1e39, 1}}}}}}}),
      {"/materials/0/extensions/KHR_materials_specular/specularColorFactor"});
  expect_error(with_material({{"extensions", {{"KHR_materials_volume", {{"thicknessFactor", 1e300}}}}}}),
               {"/materials/0/extensions/KHR_materials_volume/thicknessFactor", "in [0, 3.40282e+38]"});
}

// KHR_materials_ior sets no maximum: an ior of 1e308 is valid glTF. It is kept as the largest
// float, the same fully reflecting surface, instead of infinity (which shaded as NaN).
TEST(GltfLoaderErrors, AnIorPastTheLargestFloatIsKeptAtIt) {
  for (const double ior : {1e308, 1e39}) {
    gltf_builder b = single_triangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["materials"] = json::array({json{{"extensions", {{"KHR_materials_ior", {{"ior", ior}}}}}}});
    temp_folder dir;
    const scene s = load_gltf(b.write(dir.file("ior.gltf")));
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].ior, std::numeric_limits<float>::max()) << ior;
  }
}

TEST(GltfLoaderErrors, BadCameras) {
  {
    gltf_builder b = single_triangle();
    b.doc["cameras"] =
        json::array({json{{"type", "perspective"}, {"perspective", {{"yfov", 3.5}, {"znear", 0.1}}}}});
    expect_error(b, {"/cameras/0/perspective/yfov", "not in (0, pi)"});
  }
  {
    gltf_builder b = single_triangle();
    b.doc["cameras"] = json::array({json{
        {"type", "orthographic"}, {"orthographic", {{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}}}});
    expect_error(b, {"/cameras/0/orthographic", "must not be zero"});
  }
}

TEST(GltfLoaderErrors, MissingFile) {
  temp_folder dir;
  const std::string path = dir.file("nope.gltf");
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_EQ(message, path + ": cannot open file: No such file or directory");
}

TEST(GltfLoaderErrors, MissingBin) {
  temp_folder dir;
  const std::string path = single_triangle().write_external(dir.file("scene.gltf"), "missing.bin", false);
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("missing.bin"), std::string::npos) << message;
}

TEST(GltfLoaderErrors, MissingImageFile) {
  gltf_builder b = single_triangle();
  b.doc["images"] = json::array({json{{"uri", "gone.png"}}});
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  expect_error(b, {"/images/0/uri", "cannot read image file 'gone.png'"});
}

TEST(GltfLoaderErrors, NotJson) {
  temp_folder dir;
  const std::string path = dir.file("text.gltf");
  write_text(path, "this is not json at all");
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("invalid glTF"), std::string::npos) << message;
}

TEST(GltfLoaderErrors, UnsupportedAssetVersion) {
  gltf_builder b = single_triangle();
  b.doc["asset"]["version"] = "1.0";
  expect_error(b, {"/asset/version", "not supported"});
}

// GLB container damage, each checked before tinygltf sees the bytes.
class GlbErrors : public ::testing::Test {
 protected:
  std::string load_error(const std::vector<uint8_t>& bytes) {
    const std::string path = dir_.file("broken.glb");
    write_bytes(path, bytes);
    return error_of([&] { load_gltf(path); });
  }
  static void put_u32(std::vector<uint8_t>& bytes, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (8 * i));
  }
  temp_folder dir_;
  std::vector<uint8_t> good_ = single_triangle().glb_bytes();
};

TEST_F(GlbErrors, Truncated) {
  std::vector<uint8_t> bytes(good_.begin(), good_.end() - 10);
  const std::string message = load_error(bytes);
  EXPECT_NE(message.find("header declares"), std::string::npos) << message;
}

TEST_F(GlbErrors, TruncatedWithMatchingLength) {
  std::vector<uint8_t> bytes(good_.begin(), good_.end() - 8);
  put_u32(bytes, 8, static_cast<uint32_t>(bytes.size()));
  const std::string message = load_error(bytes);
  EXPECT_NE(message.find("chunk 1 needs"), std::string::npos) << message;
}

TEST_F(GlbErrors, ShorterThanHeader) {
  const std::string message = load_error({'g', 'l', 'T', 'F', 2, 0});
  EXPECT_NE(message.find("shorter than the 12-byte GLB header"), std::string::npos) << message;
}

TEST_F(GlbErrors, BadMagic) {
  std::vector<uint8_t> bytes = good_;
  bytes[0] = 'x';
  const std::string message = load_error(bytes);
  EXPECT_NE(message.find("bad magic"), std::string::npos) << message;
}

TEST_F(GlbErrors, BadVersion) {
  std::vector<uint8_t> bytes = good_;
  put_u32(bytes, 4, 1);
  const std::string message = load_error(bytes);
  EXPECT_NE(message.find("version 1"), std::string::npos) << message;
}

TEST_F(GlbErrors, UnalignedJsonChunk) {
  std::vector<uint8_t> bytes = good_;
  put_u32(bytes, 12, 5);
  const std::string message = load_error(bytes);
  EXPECT_NE(message.find("not a multiple of 4"), std::string::npos) << message;
}

TEST_F(GlbErrors, FirstChunkNotJson) {
  std::vector<uint8_t> bytes = good_;
  put_u32(bytes, 16, 0x004E4942);
  const std::string message = load_error(bytes);
  EXPECT_NE(message.find("expected JSON"), std::string::npos) << message;
}

TEST_F(GlbErrors, LoadsWhenIntact) {
  EXPECT_NO_THROW(load_gltf((write_bytes(dir_.file("ok.glb"), good_), dir_.file("ok.glb"))));
}

// The fixtures tools/make_bad_gltf.py writes for the CLI's bad-input test.
TEST(GltfLoaderErrors, BadGltfFixturesAreRefused) {
  const fs::path folder = fs::path(KILN_SOURCE_DIR) / "tests" / "data" / "bad_gltf";
  const std::map<std::string, std::string> expected = {
      {"truncated.glb", "header declares"},
      {"out_of_range_index.gltf", "/meshes/0/primitives/0/indices: index 7"},
      {"accessor_past_buffer_end.gltf", "/accessors/0: accessor reads past the end of bufferView 0"},
      {"missing_bin.gltf", "missing.bin"},
      {"unsupported_required_extension.gltf", "KHR_texture_basisu is not supported: no KTX2/Basis"},
      {"nan_matrix.gltf", "invalid glTF"},
      {"not_json.gltf", "invalid glTF"},
      {"truncated_png.gltf", "/images/0: cannot decode image"},
      {"escapes_folder.gltf", "/buffers/0/uri: '../../../../../../etc/passwd' refers to a file outside"},
  };
  for (const auto& [name, fragment] : expected) {
    const fs::path path = folder / name;
    ASSERT_TRUE(fs::exists(path)) << path << " is missing: run tools/make_bad_gltf.py";
    try {
      load_gltf(path.string());
      ADD_FAILURE() << name << " loaded";
    } catch (const kiln::error& e) {
      EXPECT_EQ(e.kind(), error_kind::input) << name;
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace kiln
