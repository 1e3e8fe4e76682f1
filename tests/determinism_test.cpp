// The image must be bit-identical for any thread count and tile size: samples are seeded by
// (pixel, sample index) alone and each pixel is computed by one task in a fixed order.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstring>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/tile_renderer.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

film render_demo(int threads, int tile_size) {
  scene world = load_gltf(demo_scene);
  embree_accelerator accel(world);
  view_camera cam = make_gltf_camera(world.cameras.at(0), 80, 60);
  render_settings settings;
  settings.samples_per_pixel = 4;
  settings.threads = threads;
  settings.tile_size = tile_size;
  return render_image(world, accel, cam, settings);
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(determinism, one_thread_and_many_threads_give_identical_bytes) {
  film one = render_demo(1, 16);
  film many = render_demo(4, 7);
  EXPECT_TRUE(same_bytes(one.color, many.color));
  EXPECT_TRUE(same_bytes(one.depth, many.depth));
  EXPECT_TRUE(same_bytes(one.vec3_layer(aov::normal), many.vec3_layer(aov::normal)));
  // The comparison is only meaningful on a real image.
  double sum = 0.0;
  for (const vec4& c : one.color) sum += c.r + c.g + c.b;
  EXPECT_GT(sum, 0.05 * one.color.size());
}

std::vector<float> read_pixels(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  return pixels;
}

TEST(determinism, cli_thread_count_does_not_change_pixels) {
  std::string dir = testing::scratch_folder("determinism");
  auto a = testing::run_kiln(
      {"render", demo_scene, "-o", dir + "/a.exr", "--width", "64", "--spp", "2", "--threads", "1", "-q"});
  auto b = testing::run_kiln({"render", demo_scene, "-o", dir + "/b.exr", "--width", "64", "--spp", "2",
                              "--threads", "3", "--tile-size", "5", "-q"});
  ASSERT_EQ(a.exit_code, 0) << a.stderr_text;
  ASSERT_EQ(b.exit_code, 0) << b.stderr_text;
  std::vector<float> pa = read_pixels(dir + "/a.exr"), pb = read_pixels(dir + "/b.exr");
  ASSERT_FALSE(pa.empty());
  EXPECT_TRUE(same_bytes(pa, pb));
}

TEST(determinism, cli_gaussian_filter_gives_identical_bytes_for_any_threads_and_tiles) {
  std::string dir = testing::scratch_folder("determinism_filter");
  std::vector<std::vector<float>> images;
  for (auto [threads, tile] : {std::pair{"1", "32"}, {"4", "5"}, {"4", "13"}}) {
    std::string out = dir + "/g" + threads + "_" + tile + ".exr";
    auto r = testing::run_kiln({"render", demo_scene, "-o", out, "--width", "64", "--spp", "3", "--filter",
                                "gaussian", "--threads", threads, "--tile-size", tile, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    images.push_back(read_pixels(out));
    ASSERT_FALSE(images.back().empty());
  }
  EXPECT_TRUE(same_bytes(images[0], images[1]));
  EXPECT_TRUE(same_bytes(images[0], images[2]));
}

}  // namespace
}  // namespace kiln
