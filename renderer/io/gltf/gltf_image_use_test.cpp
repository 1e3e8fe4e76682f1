// Images no material samples are never read from disk nor kept: a large unused image costs no
// memory and a missing one is no error, while a used image still loads (or fails) as before.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_parse.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// Writes a 2x2 RGB PNG of one colour into the folder.
void write_png(const temp_folder& dir, const std::string& name, const uint8_t rgb[3]) {
  const std::string path = dir.file(name);
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  ASSERT_TRUE(out->open(path, OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::UINT8)));
  std::vector<uint8_t> pixels;
  for (int i = 0; i < 4; ++i) pixels.insert(pixels.end(), rgb, rgb + 3);
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
}

// A triangle whose material samples image 0 through texture 0; images are the given ones.
// Texture 1 (image 1) exists but no material names it.
gltf_builder triangle_with_images(const json& images) {
  gltf_builder b = single_triangle();
  json& prim = b.doc["meshes"][0]["primitives"][0];
  prim["attributes"]["TEXCOORD_0"] = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1}, k_float, "VEC2", 2);
  prim["material"] = 0;
  b.doc["images"] = images;
  b.doc["textures"] = json::array({json{{"source", 0}}, json{{"source", 1}}});
  b.doc["materials"] = json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  return b;
}

const uint8_t orange[3] = {240, 120, 16};

void expect_orange_2x2(const scene& s) {
  ASSERT_EQ(s.images.size(), 1u);  // the unused image never becomes a scene image
  ASSERT_EQ(s.images[0].width, 2);
  ASSERT_EQ(s.images[0].height, 2);
  ASSERT_EQ(s.images[0].texels8.size(), 16u);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(s.images[0].texels8[static_cast<size_t>(c)], orange[c]);
}

// Parses the file and checks which of its two images kept encoded bytes (a used PNG starts with
// "\x89PNG"), then that it loads with the used image decoded.
void expect_kept_bytes(const std::string& path, bool first, bool second) {
  const tinygltf::Model model = gltf_internal::parse_gltf_file(path, gltf_load_options{});
  ASSERT_EQ(model.images.size(), 2u);
  const bool kept[2] = {first, second};
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(model.images[i].image.empty(), !kept[i]) << "image " << i;
    if (kept[i] && model.images[i].image.size() > 8) EXPECT_EQ(model.images[i].image[1], 'P');
  }
  expect_orange_2x2(load_gltf(path));
}

// A broken reference is refused even where its bytes would not be read.
TEST(GltfImageUse, UnusedMissingImageFileIsStillRefused) {
  temp_folder dir;
  write_png(dir, "used.png", orange);
  const gltf_builder b =
      triangle_with_images(json::array({json{{"uri", "used.png"}}, json{{"uri", "gone.png"}}}));
  const std::string path = b.write(dir.file("scene.gltf"));
  try {
    load_gltf(path);
    ADD_FAILURE() << "a missing image file loaded";
  } catch (const error& e) {
    EXPECT_NE(std::string(e.what()).find("/images/1/uri: cannot read image file 'gone.png'"),
              std::string::npos)
        << e.what();
  }
}

TEST(GltfImageUse, UnusedGarbageImageFileIsNotKept) {
  temp_folder dir;
  write_png(dir, "used.png", orange);
  write_text(dir.file("garbage.png"), "this is no image at all");
  const gltf_builder b =
      triangle_with_images(json::array({json{{"uri", "used.png"}}, json{{"uri", "garbage.png"}}}));
  expect_kept_bytes(b.write(dir.file("scene.gltf")), true, false);
}

TEST(GltfImageUse, FileNamedByUsedAndUnusedImageIsRead) {
  temp_folder dir;
  write_png(dir, "shared.png", orange);
  // Image 0 is unused, image 1 (the same file, spelt differently) is the one the material samples.
  gltf_builder b =
      triangle_with_images(json::array({json{{"uri", "shared.png"}}, json{{"uri", "./shared.png"}}}));
  b.doc["textures"] = json::array({json{{"source", 1}}, json{{"source", 0}}});
  expect_kept_bytes(b.write(dir.file("scene.gltf")), false, true);
}

TEST(GltfImageUse, ImageOfExtensionTextureInfoIsRead) {
  temp_folder dir;
  write_png(dir, "used.png", orange);
  write_png(dir, "thickness.png", orange);
  gltf_builder b =
      triangle_with_images(json::array({json{{"uri", "used.png"}}, json{{"uri", "thickness.png"}}}));
  b.doc["materials"][0]["extensions"]["KHR_materials_volume"] = {{"thicknessTexture", {{"index", 1}}}};
  expect_kept_bytes(b.write(dir.file("scene.gltf")), true, true);
}

TEST(GltfImageUse, UnusedDataUriImageBytesAreDropped) {
  temp_folder dir;
  write_png(dir, "used.png", orange);
  const gltf_builder b = triangle_with_images(json::array(
      {json{{"uri", "used.png"}}, json{{"uri", std::string("data:image/png;base64,") + png_2x2_base64}}}));
  expect_kept_bytes(b.write(dir.file("scene.gltf")), true, false);
}

TEST(GltfImageUse, UsedMissingImageFileFails) {
  temp_folder dir;
  const gltf_builder b =
      triangle_with_images(json::array({json{{"uri", "gone.png"}}, json{{"uri", "gone.png"}}}));
  const std::string path = b.write(dir.file("scene.gltf"));
  try {
    load_gltf(path);
    ADD_FAILURE() << "a missing used image must fail";
  } catch (const kiln::error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": /images/0/uri: cannot read image file 'gone.png'");
  }
}

// A 4x4 lossy WebP of pure green (made with oiiotool --pattern constant:color=0,1,0 4x4 3).
const std::vector<uint8_t> green_webp = {
    82,  73,  70,  70,  68,  0,   0,   0,   87,  69,  66,  80,  86, 80,  56,  32,  56,  0,   0,
    0,   80,  2,   0,   157, 1,   42,  4,   0,   4,   0,   0,   0,  0,   37,  160, 2,   116, 186,
    1,   248, 1,   250, 1,   252, 0,   7,   144, 0,   254, 251, 15, 139, 255, 238, 148, 37,  201,
    154, 110, 127, 251, 165, 15,  255, 233, 234, 147, 103, 201, 49, 151, 255, 167, 113, 0,   0};

// tinygltf 2.7 takes no image/webp data URI, so the WebP is a file beside the asset (as
// glTF-Transform writes it) or in a GLB bufferView.
json webp_image(const temp_folder& dir) {
  write_bytes(dir.file("green.webp"), green_webp);
  return json{{"uri", "green.webp"}};
}
json png_image() { return json{{"uri", std::string("data:image/png;base64,") + png_2x2_base64}}; }

void expect_green_4x4(const scene& s) {
  ASSERT_EQ(s.images.size(), 1u);
  ASSERT_EQ(s.images[0].width, 4);
  ASSERT_EQ(s.images[0].texels8.size(), 64u);
  EXPECT_LE(s.images[0].texels8[0], 8);  // lossy VP8: within a few levels of (0, 255, 0)
  EXPECT_GE(s.images[0].texels8[1], 247);
  EXPECT_LE(s.images[0].texels8[2], 8);
}

TEST(GltfImageUse, WebpSourceIsPreferredOverThePngFallback) {
  temp_folder dir;
  gltf_builder b = triangle_with_images(json::array({png_image(), webp_image(dir)}));
  b.doc["textures"][0]["extensions"] = {{"EXT_texture_webp", {{"source", 1}}}};
  b.doc["extensionsUsed"] = {"EXT_texture_webp"};
  expect_green_4x4(load_gltf(b.write(dir.file("webp.gltf"))));
}

TEST(GltfImageUse, RequiredWebpWithoutFallbackLoads) {
  temp_folder dir;
  gltf_builder b = triangle_with_images(json::array({webp_image(dir), png_image()}));
  b.doc["textures"][0] = {{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}};
  b.doc["extensionsUsed"] = {"EXT_texture_webp"};
  b.doc["extensionsRequired"] = {"EXT_texture_webp"};
  expect_green_4x4(load_gltf(b.write(dir.file("webp.gltf"))));
}

// A source past the images is refused like the core source, for either extension: basisu's is
// never decoded, but it was ignored, and 2^32 (an int's 0 to tinygltf) read as image 0.
TEST(GltfImageUse, ExtensionSourcesOutOfRangeAreRefused) {
  for (const char* extension : {"EXT_texture_webp", "KHR_texture_basisu"})
    for (const uint64_t source : {uint64_t(5), uint64_t(1) << 32}) {
      temp_folder dir;
      gltf_builder b = triangle_with_images(json::array({png_image(), webp_image(dir)}));
      b.doc["textures"][0]["extensions"] = {{extension, {{"source", source}}}};
      b.doc["extensionsUsed"] = {extension};
      const std::string path = b.write(dir.file("source.gltf"));
      const std::string message = error_of([&] { load_gltf(path); });
      EXPECT_EQ(message, path + ": /textures/0/extensions/" + extension + "/source: /images/" +
                             std::to_string(source) + " does not exist (file has 2 images)");
    }
}

TEST(GltfImageUse, OptionalBasisuFallsBackToThePngSource) {
  temp_folder dir;
  // Image 1 stands for the KTX2 file: never decoded, so its bytes need not be a KTX2.
  write_bytes(dir.file("stand_in.ktx2"), {0, 0, 0, 0});
  gltf_builder b = triangle_with_images(json::array({png_image(), json{{"uri", "stand_in.ktx2"}}}));
  b.doc["textures"][0]["extensions"] = {{"KHR_texture_basisu", {{"source", 1}}}};
  b.doc["extensionsUsed"] = {"KHR_texture_basisu"};
  const scene s = load_gltf(b.write(dir.file("basisu.gltf")));
  ASSERT_EQ(s.images.size(), 1u);
  EXPECT_EQ(s.images[0].width, 2);  // the 2x2 PNG
}

}  // namespace
}  // namespace kiln
