// Input an adversarial tester found loading silently or reported badly: each is refused with
// one line naming the file, the JSON pointer and the problem, and echoes user text cut short.
#include <gtest/gtest.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// Loads the builder's file; returns the one-line message, checked to start with the file name.
std::string message_of(const gltf_builder& b) {
  temp_folder dir;
  const std::string path = b.write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  return message;
}

// A triangle whose material samples image 0, which has the given URI.
gltf_builder textured_triangle(const std::string& image_uri) {
  gltf_builder b = single_triangle();
  b.doc["images"] = json::array({json{{"uri", image_uri}}});
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  return b;
}

TEST(GltfStrictInput, AnEightMegabyteUriIsShownCutShort) {
  const std::string uri = std::string(8000000, 'a') + ".png";
  const std::string message = message_of(textured_triangle(uri));
  EXPECT_LT(message.size(), 600u);
  EXPECT_NE(message.find("/images/0/uri: 'aaaa"), std::string::npos) << message.substr(0, 300);
  EXPECT_NE(message.find("...' (8000004 bytes) cannot name a file"), std::string::npos)
      << message.substr(0, 600);
}

TEST(GltfStrictInput, ALongBufferUriIsShownCutShort) {
  gltf_builder b = single_triangle();
  json doc = b.finished(std::string(100000, 'b') + ".bin");
  temp_folder dir;
  const std::string path = dir.file("scene.gltf");
  write_text(path, doc.dump());
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_LT(message.size(), 600u);
  EXPECT_NE(message.find("/buffers/0/uri: 'bbbb"), std::string::npos) << message.substr(0, 300);
  EXPECT_NE(message.find("...' (100004 bytes) cannot name a file"), std::string::npos)
      << message.substr(0, 600);
}

// A missing image whose name is long but possible: the "cannot read" message cuts it too.
TEST(GltfStrictInput, ALongMissingImageNameIsShownCutShort) {
  const std::string uri = std::string(250, 'c') + ".png";
  const std::string message = message_of(textured_triangle(uri));
  EXPECT_NE(
      message.find("/images/0/uri: cannot read image file '" + std::string(200, 'c') + "...' (254 bytes)"),
      std::string::npos)
      << message;
}

// ---- integer properties: read as JSON integers and range-checked before tinygltf narrows them --

// single_triangle with `edit` applied to its JSON; the error must name `where` and `reason`.
template <typename Edit>
void expect_refused(Edit edit, const std::string& where, const std::string& reason) {
  gltf_builder b = single_triangle();
  edit(b.doc);
  const std::string message = message_of(b);
  EXPECT_NE(message.find(": " + where + ": " + reason), std::string::npos) << message;
}

TEST(GltfStrictInput, AChildIndexPastTwoToThe32IsOutOfRangeNotTruncated) {
  // 2^32 + 1 used to read as 1 ("node is its own child"), 2^32 as 0.
  for (const int64_t index : {int64_t(4294967297), int64_t(4294967296)})
    expect_refused(
        [&](json& doc) {
          doc["nodes"].push_back(json{{"children", {index}}});
          doc["scenes"][0]["nodes"].push_back(1);
        },
        "/nodes/1/children/0", "/nodes/" + std::to_string(index) + " does not exist (file has 2 nodes)");
  expect_refused([](json& doc) { doc["nodes"][0]["mesh"] = uint64_t(18446744073709551615u); },
                 "/nodes/0/mesh", "/meshes/18446744073709551615 does not exist (file has 1 meshes)");
}

TEST(GltfStrictInput, AQuadricPrimitivePastTwoToThe32IsOutOfRange) {
  expect_refused(
      [](json& doc) {
        doc["extensionsUsed"] = {"KILN_quadric"};
        doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", "sphere"}, {"radius", 1.0}}};
        doc["nodes"].push_back(
            json{{"extensions", {{"KILN_quadric", {{"primitive", int64_t(4294967296)}}}}}});
        doc["scenes"][0]["nodes"].push_back(1);
      },
      "/nodes/1/extensions/KILN_quadric/primitive",
      "/extensions/KILN_quadric/primitives/4294967296 does not exist (file has 1 quadric definitions)");
}

TEST(GltfStrictInput, NegativeIndicesAreRefused) {
  const std::string negative = "index -1 is negative";
  expect_refused([](json& doc) { doc["nodes"][0]["mesh"] = -1; }, "/nodes/0/mesh", negative);
  expect_refused([](json& doc) { doc["meshes"][0]["primitives"][0]["material"] = -1; },
                 "/meshes/0/primitives/0/material", negative);
  expect_refused([](json& doc) { doc["accessors"][0]["bufferView"] = -1; }, "/accessors/0/bufferView",
                 negative);
  expect_refused([](json& doc) { doc["scene"] = -1; }, "/scene", negative);
  expect_refused(
      [](json& doc) {
        doc["materials"] =
            json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", -1}}}}}}});
        doc["meshes"][0]["primitives"][0]["material"] = 0;
      },
      "/materials/0/pbrMetallicRoughness/baseColorTexture/index", negative);
  expect_refused(
      [](json& doc) {
        doc["textures"] = json::array({json{{"source", -1}}});
      },
      "/textures/0/source", negative);
}

TEST(GltfStrictInput, FractionalAndNonNumericIndicesAreRefused) {
  expect_refused([](json& doc) { doc["nodes"][0]["mesh"] = 0.5; }, "/nodes/0/mesh",
                 "an index must be an integer, got 0.5");
  expect_refused([](json& doc) { doc["nodes"][0]["mesh"] = 0.0; }, "/nodes/0/mesh",
                 "an index must be an integer, got 0.0");
  expect_refused([](json& doc) { doc["nodes"][0]["mesh"] = "0"; }, "/nodes/0/mesh",
                 "an index must be an integer, got \"0\"");
  expect_refused([](json& doc) { doc["scenes"][0]["nodes"][0] = 1e300; }, "/scenes/0/nodes/0",
                 "an index must be an integer, got 1e+300");
}

TEST(GltfStrictInput, ByteOffsetsAndCountsFollowTheSchemaMinimums) {
  expect_refused([](json& doc) { doc["accessors"][0]["byteOffset"] = -4; }, "/accessors/0/byteOffset",
                 "byteOffset must be at least 0, got -4");
  expect_refused([](json& doc) { doc["bufferViews"][0]["byteOffset"] = -12; }, "/bufferViews/0/byteOffset",
                 "byteOffset must be at least 0, got -12");
  expect_refused([](json& doc) { doc["accessors"][0]["count"] = 0; }, "/accessors/0/count",
                 "count must be at least 1, got 0");
  expect_refused([](json& doc) { doc["accessors"][0]["byteOffset"] = 1.5; }, "/accessors/0/byteOffset",
                 "byteOffset must be an integer, got 1.5");
}

TEST(GltfStrictInput, EnumsPastIntAreRefusedNotTruncated) {
  // 2^32 + 5126 would read as FLOAT.
  expect_refused([](json& doc) { doc["accessors"][0]["componentType"] = int64_t(4294972422); },
                 "/accessors/0/componentType",
                 "componentType is 4294972422, larger than kiln reads (at most 2147483647)");
}

TEST(GltfStrictInput, ExplicitZeroIndicesStillLoad) {
  gltf_builder b = single_triangle();
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["materials"] = json::array({json{{"name", "plain"}}});
  temp_folder dir;
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  EXPECT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.meshes.at(0).indices.size(), 3u);
}

// ---- cameras and node matrices --------------------------------------------------------------------

// single_triangle plus a perspective camera with these parameters, placed by node 1.
void expect_camera_refused(const json& perspective, const std::string& where, const std::string& reason) {
  expect_refused(
      [&](json& doc) {
        doc["cameras"] = json::array({json{{"type", "perspective"}, {"perspective", perspective}}});
        doc["nodes"].push_back(json{{"camera", 0}, {"translation", {0, 0, 5}}});
        doc["scenes"][0]["nodes"].push_back(1);
      },
      where, reason);
}

TEST(GltfStrictInput, CameraNumbersFollowTheSchema) {
  const std::string at = "/cameras/0/perspective/";
  expect_camera_refused({{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", 0}}, at + "aspectRatio",
                        "aspectRatio must be a number greater than 0, got 0");
  expect_camera_refused({{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", -1.5}}, at + "aspectRatio",
                        "aspectRatio must be a number greater than 0, got -1.5");
  expect_camera_refused({{"yfov", 0.8}, {"znear", 0}}, at + "znear", "znear must be greater than 0, got 0");
  expect_camera_refused({{"yfov", 0.8}, {"znear", -1}}, at + "znear", "znear must be greater than 0, got -1");
  expect_camera_refused({{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 0}}, at + "zfar",
                        "zfar must be greater than znear and 0, got 0");
  expect_camera_refused({{"yfov", 0.8}, {"znear", 1}, {"zfar", 1}}, at + "zfar",
                        "zfar must be greater than znear and 0, got 1");
}

TEST(GltfStrictInput, NonAffineNodeMatricesAreRefused) {
  expect_refused(
      [](json& doc) { doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2}; },
      "/nodes/0/matrix", "the last row must be 0, 0, 0, 1 (a node matrix is affine), got 0, 0, 0, 2");
  expect_refused(
      [](json& doc) { doc["nodes"][0]["matrix"] = {1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
      "/nodes/0/matrix", "the last row must be 0, 0, 0, 1 (a node matrix is affine), got 0.5, 0, 0, 1");
}

}  // namespace
}  // namespace kiln
