// Crops: a region rendered alone holds exactly the bytes of the same pixels of the full frame, for
// filters that reach across the region's border and for adaptive sampling.
#include <gtest/gtest.h>

#include <cstring>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/tile_renderer.h"

namespace kiln {
namespace {

constexpr int width = 40, height = 30;

struct cornell {
  scene world = load_gltf(std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf");
  embree_accelerator accel{world};
  view_camera cam = make_gltf_camera(world.cameras.at(0), width, height);
};

film render(const cornell& c, render_settings s, const pixel_rect& crop = {}) {
  for (aov a : {aov::position, aov::albedo, aov::uv, aov::ids}) s.aovs.set(a);
  s.crop = crop;
  s.tile_size = 8;
  s.threads = 2;
  return render_image(c.world, c.accel, c.cam, s);
}

// Every buffer of the crop equals the full frame's pixels in the crop's region, byte for byte.
template <typename T>
void expect_same_region(const std::vector<T>& crop, const film& cf, const std::vector<T>& full,
                        const film& ff, const char* what) {
  ASSERT_EQ(crop.size(), size_t(cf.width) * cf.height) << what;
  int differing = 0;
  for (int y = 0; y < cf.height; ++y)
    for (int x = 0; x < cf.width; ++x)
      differing += std::memcmp(&crop[cf.index(x, y)], &full[ff.index(x + cf.x0, y + cf.y0)], sizeof(T)) != 0;
  EXPECT_EQ(differing, 0) << what;
}

void expect_crop_matches(const cornell& c, const render_settings& s, const pixel_rect& r) {
  const film full = render(c, s), crop = render(c, s, r);
  EXPECT_EQ(crop.width, r.width());
  EXPECT_EQ(crop.height, r.height());
  EXPECT_EQ(crop.x0, r.x0);
  EXPECT_EQ(crop.y0, r.y0);
  EXPECT_EQ(crop.full_width, width);
  EXPECT_EQ(crop.full_height, height);
  expect_same_region(crop.color, crop, full.color, full, "colour");
  expect_same_region(crop.depth, crop, full.depth, full, "depth");
  expect_same_region(crop.vec3_layer(aov::normal), crop, full.vec3_layer(aov::normal), full, "normal");
  expect_same_region(crop.vec3_layer(aov::position), crop, full.vec3_layer(aov::position), full, "position");
  expect_same_region(crop.vec3_layer(aov::albedo), crop, full.vec3_layer(aov::albedo), full, "albedo");
  expect_same_region(crop.uv, crop, full.uv, full, "uv");
  expect_same_region(crop.ids, crop, full.ids, full, "ids");
}

const pixel_rect crops[] = {{5, 3, 22, 17}, {0, 0, 9, 30}, {31, 20, 40, 30}, {13, 13, 14, 14}};

TEST(crop, filtered_crops_match_the_full_frame) {
  cornell c;
  render_settings s;
  s.samples_per_pixel = 4;
  s.filter = {filter_kind::gaussian, 1.5f};  // reaches one pixel across the crop's border
  for (const pixel_rect& r : crops) expect_crop_matches(c, s, r);
  s.filter = {filter_kind::blackman_harris, 3.0f};  // three pixels
  expect_crop_matches(c, s, crops[0]);
}

TEST(crop, adaptive_crops_match_the_full_frame) {
  cornell c;
  render_settings s;
  s.adaptive = {0.05f, 2};
  for (const pixel_rect& r : crops) expect_crop_matches(c, s, r);
}

TEST(crop, regions_outside_the_image_are_refused) {
  cornell c;
  EXPECT_THROW(render(c, render_settings{}, {30, 0, 41, 10}), error);
  EXPECT_THROW(render(c, render_settings{}, {-1, 0, 10, 10}), error);
}

}  // namespace
}  // namespace kiln
