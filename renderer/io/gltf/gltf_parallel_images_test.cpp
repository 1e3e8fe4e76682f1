// A scene's images decode together, in parallel: the loaded scene is the same for any thread
// count, and the error is always the one a decode in scene order would meet first, whether it is
// an image's or a material's.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// Writes a size x (size + 1) RGB PNG whose texels are all (seed, 2 seed, 3 seed) mod 256.
void write_png(const std::string& path, int size, int seed) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  ASSERT_TRUE(out->open(path, OIIO::ImageSpec(size, size + 1, 3, OIIO::TypeDesc::UINT8)));
  std::vector<uint8_t> pixels;
  for (int i = 0; i < size * (size + 1); ++i)
    for (int c = 1; c <= 3; ++c) pixels.push_back(uint8_t(seed * c));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
}

// count triangles, triangle i with material i whose base colour samples image i (image<i>.png);
// the images listed in broken hold bytes that are no image.
gltf_builder textured_triangles(const temp_folder& dir, int count, const std::vector<int>& broken = {}) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int uv = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1}, k_float, "VEC2", 2);
  std::vector<int> roots;
  for (int i = 0; i < count; ++i) {
    const int mesh = b.add_mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"material", i}});
    roots.push_back(b.add_node({{"mesh", mesh}}));
    const std::string name = "image" + std::to_string(i) + ".png";
    if (std::find(broken.begin(), broken.end(), i) != broken.end())
      write_text(dir.file(name), "this is not an image");
    else
      write_png(dir.file(name), 3 + i, 11 * i + 5);
    b.doc["images"].push_back(json{{"uri", name}});
    b.doc["textures"].push_back(json{{"source", i}});
    b.doc["materials"].push_back(json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
  }
  b.set_scene(roots);
  return b;
}

scene load_with_threads(const std::string& path, int threads) {
  gltf_load_options options;
  options.threads = threads;
  return load_gltf(path, options);
}

TEST(GltfParallelImages, SceneIsTheSameForAnyThreadCount) {
  temp_folder dir;
  const int count = 24;
  const std::string path = textured_triangles(dir, count).write(dir.file("scene.gltf"));
  const scene one = load_with_threads(path, 1);
  ASSERT_EQ(one.images.size(), size_t(count));
  for (int i = 0; i < count; ++i) {
    const image& im = one.images[size_t(i)];
    EXPECT_EQ(im.name, "image" + std::to_string(i) + ".png");
    ASSERT_EQ(im.width, 3 + i);
    ASSERT_EQ(im.height, 4 + i);
    ASSERT_EQ(im.texels8.size(), size_t(im.width * im.height * 4));
    EXPECT_EQ(im.texels8[0], uint8_t(11 * i + 5));
    EXPECT_EQ(im.texels8[im.texels8.size() - 2], uint8_t(3 * (11 * i + 5)));
    EXPECT_EQ(im.texels8.back(), 255);
  }
  for (int threads : {2, 4, 8}) {
    const scene many = load_with_threads(path, threads);
    ASSERT_EQ(many.images.size(), one.images.size());
    for (size_t i = 0; i < one.images.size(); ++i) {
      EXPECT_EQ(many.images[i].name, one.images[i].name);
      EXPECT_EQ(many.images[i].texels8, one.images[i].texels8)
          << "image " << i << ", " << threads << " threads";
    }
    for (size_t t = 0; t < one.textures.size(); ++t) EXPECT_EQ(many.textures[t].image, one.textures[t].image);
  }
}

TEST(GltfParallelImages, FirstBrokenImageInSceneOrderIsReported) {
  temp_folder dir;
  const std::string path = textured_triangles(dir, 16, {13, 6, 9}).write(dir.file("scene.gltf"));
  for (int round = 0; round < 4; ++round)
    for (int threads : {1, 4}) {
      const std::string message = error_of([&] { load_with_threads(path, threads); });
      EXPECT_NE(message.find("/images/6: image data is not PNG, JPEG, WebP, GIF or BMP"), std::string::npos)
          << message;
    }
}

// Material 1's error comes after image 0 was met: the image's error is the one reported, as when
// each image decoded the moment a material named it.
TEST(GltfParallelImages, ImageMetBeforeABadMaterialIsReportedFirst) {
  temp_folder dir;
  gltf_builder b = textured_triangles(dir, 3, {0});
  b.doc["materials"][1]["emissiveFactor"] = json::array({-1, 0, 0});
  const std::string path = b.write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_with_threads(path, 2); });
  EXPECT_NE(message.find("/images/0: image data is not PNG"), std::string::npos) << message;
}

TEST(GltfParallelImages, BadMaterialBeforeABrokenImageIsReportedFirst) {
  temp_folder dir;
  gltf_builder b = textured_triangles(dir, 3, {1});
  b.doc["materials"][0]["emissiveFactor"] = json::array({-1, 0, 0});
  const std::string path = b.write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_with_threads(path, 2); });
  EXPECT_NE(message.find("/materials/0/emissiveFactor: emissiveFactor must be finite and not negative"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace kiln
