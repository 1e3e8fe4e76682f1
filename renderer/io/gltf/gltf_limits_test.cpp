// Resource limits: files that would exhaust the stack, memory or time are refused with a message
// that names the limit and the option that raises it.
#include <gtest/gtest.h>
#include <stdlib.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// A PNG whose header declares 65536 x 65536 RGBA texels (16 GiB decoded) and holds almost nothing.
constexpr const char* png_huge_base64 =
    "iVBORw0KGgoAAAANSUhEUgABAAAAAQAACAYAAABshDDjAAAADElEQVR4nGNgoAwAAABAAAG3NHzvAAAAAElFTkSuQmCC";

std::string load_error(const std::string& path, const gltf_load_options& options = {}) {
  return error_of([&] { load_gltf(path, options); });
}

TEST(GltfLimits, DeeplyNestedJsonIsRefusedBeforeParsing) {
  temp_folder dir;
  const size_t depth = 200000;  // enough to overflow a parser's recursion
  const std::string text = "{\"asset\":{\"version\":\"2.0\",\"extras\":" + std::string(depth, '[') +
                           std::string(depth, ']') + "}}";
  const std::string path = dir.file("nested.gltf");
  write_text(path, text);
  const std::string message = load_error(path);
  EXPECT_NE(message.find("nests deeper than 512 levels (--max-json-depth)"), std::string::npos) << message;
}

TEST(GltfLimits, BracketsInsideStringsDoNotCountAsNesting) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["asset"]["generator"] = std::string(2000, '[') + "\\\"" + std::string(2000, '{');
  EXPECT_EQ(load_gltf(b.write(dir.file("scene.gltf"))).meshes.size(), 1u);
}

TEST(GltfLimits, DepthLimitIsOverridable) {
  temp_folder dir;
  const std::string path = single_triangle().write(dir.file("scene.gltf"));
  gltf_load_options options;
  options.limits.max_json_depth = 3;  // the triangle's accessors nest 4 deep
  EXPECT_NE(load_error(path, options).find("nests deeper than 3"), std::string::npos);
}

TEST(GltfLimits, TooManyNodesIsRefusedNamingTheLimit) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.add_node(json::object());
  b.add_node(json::object());
  const std::string path = b.write(dir.file("scene.gltf"));
  gltf_load_options options;
  options.limits.max_nodes = 2;
  const std::string message = load_error(path, options);
  EXPECT_NE(message.find("/nodes: 3 nodes, over the limit of 2 (--max-nodes)"), std::string::npos) << message;
  options.limits.max_nodes = 3;
  EXPECT_EQ(load_gltf(path, options).instances.size(), 1u);
}

TEST(GltfLimits, OversizedJsonIsRefused) {
  temp_folder dir;
  const std::string path = single_triangle().write(dir.file("scene.gltf"));
  gltf_load_options options;
  options.limits.max_json_bytes = 64;
  EXPECT_NE(load_error(path, options).find("over the limit of 64 (--max-json-bytes)"), std::string::npos);
}

TEST(GltfLimits, ImageWithHugeDeclaredSizeIsRefusedWithoutDecoding) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["images"] = json::array({json{{"uri", std::string("data:image/png;base64,") + png_huge_base64}}});
  const std::string message = load_error(b.write(dir.file("scene.gltf")));
  EXPECT_NE(message.find("/images/0"), std::string::npos) << message;
  EXPECT_NE(message.find("over the limit of 268435456 (--max-texels)"), std::string::npos) << message;
}

// A 24-byte progressive JPEG (SOF2) claiming 20000x20000: its size comes from the frame header,
// so it is refused before a decoder runs (OpenImageIO's JPEG reader allocated the whole frame,
// 2.4 GB, while opening such a file), and without loading the image codecs module at all.
TEST(GltfLimits, ProgressiveJpegWithHugeDeclaredSizeIsRefusedBeforeAnyDecoder) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["textures"] = json::array({json{{"source", 0}}});
  const std::vector<uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xC2, 0x00, 0x11, 0x08, 0x4E, 0x20, 0x4E, 0x20, 0x03,
                                     0x01, 0x22, 0x00, 0x02, 0x11, 0x01, 0x03, 0x11, 0x01, 0xFF, 0xD9};
  b.doc["images"] = json::array({json{{"uri", "data:image/jpeg;base64," + base64_encode(jpeg)}}});
  const std::string path = b.write(dir.file("scene.gltf"));
  ::setenv("KILN_IMAGE_CODECS", "/nonexistent/codecs.so", 1);  // a decode would fail on the module
  const std::string message = load_error(path);
  ::unsetenv("KILN_IMAGE_CODECS");
  EXPECT_NE(
      message.find("/images/0: image is 20000x20000 texels, over the limit of 268435456 (--max-texels)"),
      std::string::npos)
      << message;
}

TEST(GltfLimits, TexelLimitIsOverridable) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["images"] = json::array({json{{"uri", std::string("data:image/png;base64,") + png_2x2_base64}}});
  const std::string path = b.write(dir.file("scene.gltf"));
  EXPECT_EQ(load_gltf(path).images.size(), 1u);  // 4 texels: well within the default
  gltf_load_options options;
  options.limits.max_texels = 3;
  const std::string message = load_error(path, options);
  EXPECT_NE(message.find("/images/0: image is 2x2 texels, over the limit of 3 (--max-texels)"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace kiln
