// What tinygltf would refuse in its own words is refused before it parses, at the JSON pointer of
// the value at fault: numbers beyond a double, JSON syntax, buffer sources and sizes, byteStride,
// index accessors without data, spot lights without their cone.
#include <gtest/gtest.h>

#include <functional>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

struct refusal {
  std::string location;
  std::string reason;
};

refusal refusal_of(const std::string& path) {
  try {
    load_gltf(path);
  } catch (const kiln::error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return {e.location(), e.reason()};
  }
  ADD_FAILURE() << "loaded";
  return {};
}

// The single triangle as text, with its buffer as a data URI, edited by `edit`.
std::string write_edited(const temp_folder& dir, const std::function<void(json&)>& edit) {
  gltf_builder b = single_triangle();
  json doc = b.finished("data:application/octet-stream;base64," + base64_encode(b.bin));
  edit(doc);
  const std::string path = dir.file("scene.gltf");
  write_text(path, doc.dump());
  return path;
}

TEST(GltfPrecheck, NumberBeyondADoubleIsRefusedAtItsPointer) {
  temp_folder dir;
  const std::string path = dir.file("scene.gltf");
  json doc = single_triangle().finished("x.bin");
  doc["nodes"][0]["translation"] = {0.0, 12345.5, 0.0};
  std::string text = doc.dump();
  text.replace(text.find("12345.5"), 7, "1e309");
  write_text(path, text);
  const refusal r = refusal_of(path);
  EXPECT_EQ(r.location, "/nodes/0/translation/1");
  EXPECT_NE(r.reason.find("1e309"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("finite"), std::string::npos) << r.reason;
}

TEST(GltfPrecheck, SyntaxErrorNamesLineAndColumnAndTheEnclosingValue) {
  temp_folder dir;
  const std::string path = dir.file("scene.gltf");
  write_text(path, "{\"asset\": {\"version\": \"2.0\"},\n \"nodes\": [{}, {\"name\": }]}");
  const refusal r = refusal_of(path);
  EXPECT_EQ(r.location, "/nodes/1");
  EXPECT_NE(r.reason.find("not JSON"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("line 2"), std::string::npos) << r.reason;
}

TEST(GltfPrecheck, JsonThatIsNotAnObjectIsRefused) {
  temp_folder dir;
  const std::string path = dir.file("scene.gltf");
  write_text(path, "[1, 2]");
  EXPECT_NE(refusal_of(path).reason.find("array, not an object"), std::string::npos);
}

TEST(GltfPrecheck, MalformedDataUriHeaderAndPayload) {
  temp_folder dir;
  refusal r = refusal_of(write_edited(
      dir, [](json& d) { d["buffers"][0]["uri"] = "data:application/octet-stream;;base64,AA=="; }));
  EXPECT_EQ(r.location, "/buffers/0/uri");
  EXPECT_NE(r.reason.find("malformed data URI"), std::string::npos) << r.reason;
  r = refusal_of(write_edited(
      dir, [](json& d) { d["buffers"][0]["uri"] = "data:application/octet-stream;base64,A=AA"; }));
  EXPECT_EQ(r.location, "/buffers/0/uri");
  EXPECT_NE(r.reason.find("base64"), std::string::npos) << r.reason;
}

// Exporters differ in padding and MIME type; what tinygltf decodes must still load.
TEST(GltfPrecheck, UnpaddedBase64AndOtherTinygltfHeadersLoad) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.bin.resize(b.bin.size() + 2);  // 44 bytes: base64 pads with one '='
  std::string unpadded = base64_encode(b.bin);
  ASSERT_EQ(unpadded.back(), '=');
  while (unpadded.back() == '=') unpadded.pop_back();
  for (const std::string header :
       {"data:application/gltf-buffer;base64,", "data:application/octet-stream;base64,"}) {
    const std::string path = dir.file("scene.gltf");
    write_text(path, b.finished(header + unpadded).dump());
    const scene s = load_gltf(path);
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].positions[2], vec3(0, 1, 0));
  }
}

TEST(GltfPrecheck, ByteLengthMustMatchTheDataUri) {
  temp_folder dir;
  const refusal r = refusal_of(write_edited(
      dir, [](json& d) { d["buffers"][0]["byteLength"] = d["buffers"][0]["byteLength"].get<int>() + 4; }));
  EXPECT_EQ(r.location, "/buffers/0/byteLength");
  EXPECT_NE(r.reason.find("the data URI holds " + std::to_string(single_triangle().bin.size()) + " bytes"),
            std::string::npos)
      << r.reason;
}

TEST(GltfPrecheck, MissingAndMisSizedBufferFiles) {
  temp_folder dir;
  const gltf_builder b = single_triangle();
  refusal r = refusal_of(b.write_external(dir.file("scene.gltf"), "gone.bin", /*write_bin=*/false));
  EXPECT_EQ(r.location, "/buffers/0/uri");
  EXPECT_NE(r.reason.find("'gone.bin' not found"), std::string::npos) << r.reason;
  const std::string path = b.write_external(dir.file("scene.gltf"), "long.bin");
  std::vector<uint8_t> longer = b.bin;
  longer.resize(longer.size() + 8);
  write_bytes(dir.file("long.bin"), longer);
  r = refusal_of(path);
  EXPECT_EQ(r.location, "/buffers/0/byteLength");
  EXPECT_NE(r.reason.find("has " + std::to_string(longer.size()) + " bytes"), std::string::npos) << r.reason;
}

TEST(GltfPrecheck, BufferWithoutASourceInAGltf) {
  temp_folder dir;
  const refusal r = refusal_of(write_edited(dir, [](json& d) { d["buffers"][0].erase("uri"); }));
  EXPECT_EQ(r.location, "/buffers/0");
  EXPECT_NE(r.reason.find("no 'uri'"), std::string::npos) << r.reason;
}

TEST(GltfPrecheck, ByteStrideMustBeAMultipleOfFour) {
  temp_folder dir;
  const refusal r = refusal_of(write_edited(dir, [](json& d) { d["bufferViews"][0]["byteStride"] = 6; }));
  EXPECT_EQ(r.location, "/bufferViews/0/byteStride");
  EXPECT_NE(r.reason.find("got 6"), std::string::npos) << r.reason;
}

TEST(GltfPrecheck, IndexAccessorNeedsABufferView) {
  temp_folder dir;
  const refusal r = refusal_of(write_edited(dir, [](json& d) { d["accessors"][1].erase("bufferView"); }));
  EXPECT_EQ(r.location, "/meshes/0/primitives/0/indices");
  EXPECT_NE(r.reason.find("index accessor 1 has no valid bufferView"), std::string::npos) << r.reason;
}

TEST(GltfPrecheck, SpotLightNeedsItsSpotObject) {
  temp_folder dir;
  const refusal r = refusal_of(write_edited(dir, [](json& d) {
    d["extensionsUsed"] = {"KHR_lights_punctual"};
    d["extensions"]["KHR_lights_punctual"]["lights"] = {json{{"type", "point"}}, json{{"type", "spot"}}};
  }));
  EXPECT_EQ(r.location, "/extensions/KHR_lights_punctual/lights/1");
}

}  // namespace
}  // namespace kiln
