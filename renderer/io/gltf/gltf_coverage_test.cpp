// Loader tests for glTF features otherwise met only in the optional asset suite: images stored in
// a .glb's bufferViews, JPEG images, meshes whose primitives use different materials, and normal
// maps on flat-shaded primitives (no NORMAL). Images are encoded at test time with OpenImageIO.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"
#include "io/gltf/mesh_tangents.h"

namespace kiln {
namespace {

using namespace gltf_test;

// Encodes RGB8 pixels (rows top to bottom) as a file of the extension's format; returns its bytes.
std::vector<uint8_t> encode_rgb(const temp_folder& dir, const std::string& name, int width, int height,
                                const std::vector<uint8_t>& rgb) {
  const std::string path = dir.file(name);
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("Compression", "jpeg:100");  // ignored by PNG
  EXPECT_TRUE(out->open(path, spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
  out->close();
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// 16x8 pixels: the left half one colour, the right half another.
const uint8_t left_colour[3] = {200, 40, 40}, right_colour[3] = {30, 90, 220};
std::vector<uint8_t> two_halves() {
  std::vector<uint8_t> rgb;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const uint8_t* c = x < 8 ? left_colour : right_colour;
      rgb.insert(rgb.end(), c, c + 3);
    }
  return rgb;
}

// A triangle with UVs whose material samples image 0 (the caller adds the image).
gltf_builder textured_triangle() {
  gltf_builder b = single_triangle();
  json& prim = b.doc["meshes"][0]["primitives"][0];
  prim["attributes"]["TEXCOORD_0"] = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1}, k_float, "VEC2", 2);
  prim["material"] = 0;
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  return b;
}

void expect_texel_near(const image& img, int x, int y, const uint8_t* rgb, int tolerance) {
  ASSERT_EQ(img.texels8.size(), static_cast<size_t>(img.width) * img.height * 4);
  const uint8_t* t = &img.texels8[(static_cast<size_t>(y) * img.width + x) * 4];
  for (int c = 0; c < 3; ++c)
    EXPECT_LE(std::abs(int(t[c]) - int(rgb[c])), tolerance) << "texel " << x << "," << y;
  EXPECT_EQ(t[3], 255);
}

TEST(GltfCoverage, ImageInGlbBufferViewDecodes) {
  temp_folder dir;
  gltf_builder b = textured_triangle();
  const std::vector<uint8_t> png = encode_rgb(dir, "halves.png", 16, 8, two_halves());
  b.doc["images"] =
      json::array({json{{"bufferView", b.add_view(png.data(), png.size())}, {"mimeType", "image/png"}}});
  const std::string path = dir.file("embedded.glb");
  write_bytes(path, b.glb_bytes());
  fs::remove(dir.file("halves.png"));  // the .glb alone must carry the image
  const scene s = load_gltf(path);
  ASSERT_EQ(s.images.size(), 1u);
  EXPECT_EQ(s.images[0].width, 16);
  EXPECT_EQ(s.images[0].height, 8);
  // PNG is lossless: every texel is exact.
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) expect_texel_near(s.images[0], x, y, x < 8 ? left_colour : right_colour, 0);
}

TEST(GltfCoverage, JpegImageDecodes) {
  temp_folder dir;
  gltf_builder b = textured_triangle();
  const std::vector<uint8_t> jpeg = encode_rgb(dir, "halves.jpg", 16, 8, two_halves());
  ASSERT_GE(jpeg.size(), 3u);
  ASSERT_EQ(jpeg[0], 0xFF);  // a JPEG stream (SOI marker)
  ASSERT_EQ(jpeg[1], 0xD8);
  b.doc["images"] = json::array({json{{"uri", "data:image/jpeg;base64," + base64_encode(jpeg)}}});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.images.size(), 1u);
  EXPECT_EQ(s.images[0].width, 16);
  EXPECT_EQ(s.images[0].height, 8);
  // JPEG is lossy (and subsamples chroma): texels away from the colour edge stay within a few levels.
  for (int y = 0; y < 8; ++y) {
    expect_texel_near(s.images[0], 2, y, left_colour, 6);
    expect_texel_near(s.images[0], 13, y, right_colour, 6);
  }
}

// libjpeg only warns about a JPEG cut short or with damaged entropy data and fills the rest with
// grey; kiln refuses it as it refuses a truncated PNG.
TEST(GltfCoverage, TruncatedOrCorruptJpegIsRefused) {
  temp_folder dir;
  std::vector<uint8_t> rgb;
  for (int i = 0; i < 64 * 64 * 3; ++i) rgb.push_back(static_cast<uint8_t>((i * 37) % 251));
  const std::vector<uint8_t> jpeg = encode_rgb(dir, "noise.jpg", 64, 64, rgb);
  std::vector<uint8_t> corrupt = jpeg;
  corrupt[corrupt.size() / 2] = 0xFF;  // a restart marker where none belongs
  corrupt[corrupt.size() / 2 + 1] = 0xD5;
  const std::vector<std::pair<std::vector<uint8_t>, std::string>> cases = {
      {std::vector<uint8_t>(jpeg.begin(), jpeg.begin() + static_cast<std::ptrdiff_t>(jpeg.size() / 2)),
       "Premature end of JPEG file"},
      {std::vector<uint8_t>(jpeg.begin(), jpeg.end() - 2), "Premature end of JPEG file"},
      {corrupt, "Corrupt JPEG data"}};
  for (const auto& [bytes, reason] : cases) {
    gltf_builder b = textured_triangle();
    b.doc["images"] = json::array({json{{"uri", "data:image/jpeg;base64," + base64_encode(bytes)}}});
    const std::string path = b.write(dir.file("scene.gltf"));
    const std::string message = error_of([&] { load_gltf(path); });
    EXPECT_EQ(message.rfind(path + ": /images/0: cannot decode image: JPEG error: " + reason, 0), 0u)
        << message;
    EXPECT_EQ(message.find("image.jpg"), std::string::npos) << message;
  }
}

TEST(GltfCoverage, PrimitivesOfOneMeshKeepTheirOwnMaterials) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  const int pos = b.add_positions({0, 0, 1, 1, 0, 1, 0, 1, 1});
  b.doc["meshes"][0]["primitives"][0]["material"] = 1;
  b.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos}}}, {"material", 0}});
  b.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos}}}});  // default material
  b.doc["materials"] =
      json::array({json{{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}},
                   json{{"name", "blue"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}}});
  b.add_node({{"mesh", 0}, {"translation", {3, 0, 0}}});
  b.set_scene({0, 1});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  // Shared by both nodes; the last two primitives read the same accessor, so they share one too.
  ASSERT_EQ(s.meshes.size(), 2u);
  ASSERT_EQ(s.instances.size(), 6u);
  const char* expected[3] = {"blue", "red", "default"};
  for (size_t i = 0; i < 6; ++i) {
    SCOPED_TRACE(i);
    const instance& inst = s.instances[i];
    EXPECT_EQ(inst.shape, i % 3 == 0 ? 0u : 1u);
    const material& m = s.materials.at(inst.material);
    EXPECT_EQ(m.name, expected[i % 3]);
    const vec4 expected_colour = i % 3 == 0 ? vec4(0, 0, 1, 1) : i % 3 == 1 ? vec4(1, 0, 0, 1) : vec4(1.0f);
    EXPECT_EQ(m.base_color_factor, expected_colour);
  }
}

// A quad in the y = 0 plane facing +y, u running along +z and glTF v along +x, no NORMAL, with a
// normal-mapped material and a TANGENT that glTF says to ignore on a flat-shaded primitive.
gltf_builder flat_normal_mapped_quad() {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0});
  const int uv = b.add_data(std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}, k_float, "VEC2", 2);
  const int tangent = b.add_data(std::vector<float>(16, 0.5f), k_float, "VEC4", 4);
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, k_ushort, "SCALAR", 1);
  b.doc["images"] = json::array({json{{"uri", std::string("data:image/png;base64,") + png_2x2_base64}}});
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["materials"] = json::array({json{{"normalTexture", {{"index", 0}}}}});
  const int mesh_index =
      b.add_mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}, {"TANGENT", tangent}}},
                  {"indices", idx},
                  {"material", 0}});
  b.set_scene({b.add_node({{"mesh", mesh_index}})});
  return b;
}

TEST(GltfCoverage, FlatShadedNormalMapGetsTangentsInItsFacePlane) {
  temp_folder dir;
  const scene s = load_gltf(flat_normal_mapped_quad().write(dir.file("scene.gltf")));
  ASSERT_EQ(s.meshes.size(), 1u);
  const mesh& m = s.meshes[0];
  EXPECT_TRUE(m.normals.empty());  // flat shading
  ASSERT_EQ(m.tangents.size(), 4u);
  for (const vec4& t : m.tangents) {
    // dP/du = +z, in the face plane (perpendicular to the face normal +y). The bitangent
    // cross(n, t) * w must point to decreasing glTF v, i.e. -x: cross(+y, +z) = +x, so w = -1.
    EXPECT_NEAR(t.x, 0.0f, 1e-6f);
    EXPECT_NEAR(t.y, 0.0f, 1e-6f);
    EXPECT_NEAR(t.z, 1.0f, 1e-6f);
    EXPECT_EQ(t.w, -1.0f);
  }
}

TEST(MeshTangents, FlatMeshUsesItsFaceNormals) {
  // Two faces folded at x = 0 (a roof ridge along z), u along +z on both: each vertex's tangent
  // is +z, perpendicular to both face normals, which the old fixed +z stand-in normal would have
  // projected away.
  mesh m;
  m.positions = {{-1, 0, 0}, {0, 1, 0}, {0, 1, 1}, {-1, 0, 1}, {1, 0, 0}, {1, 0, 1}};
  m.indices = {0, 2, 1, 0, 3, 2, 4, 1, 2, 4, 2, 5};
  const std::vector<vec2> uv = {{0, 0}, {0, 0.5f}, {1, 0.5f}, {1, 0}, {0, 1}, {1, 1}};
  const std::vector<vec4> t = generate_tangents(m, uv);
  ASSERT_EQ(t.size(), 6u);
  for (size_t i = 0; i < 6; ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(t[i].x, 0.0f, 1e-6f);
    EXPECT_NEAR(t[i].y, 0.0f, 1e-6f);
    EXPECT_NEAR(t[i].z, 1.0f, 1e-6f);
    // glTF v grows with x on both faces, so the upward-image bitangent points to -x: w = -1.
    EXPECT_EQ(t[i].w, -1.0f);
  }
}

}  // namespace
}  // namespace kiln
