// The camera-ray stage: every sample of a tile gets the ray its pixel and index seed, with where it
// comes from and the backend's hit for it; with packets the streams are the tile's runs of whole
// rows (at most max_rays rays), and rows of more samples than that are traced one ray at a time.
#include "render/camera_rays.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "render/sample_pattern.h"
#include "render/tile_renderer.h"

namespace kiln {
namespace {

// Hits nothing but answers every ray with a hit whose t is its query number, and records how the
// rays arrived: the size of each coherent stream, and the rays traced alone.
class recording_accelerator final : public accelerator {
 public:
  std::optional<hit> intersect(const ray&) const override {
    hit h;
    h.t = float(++queries);
    ++single;
    return h;
  }
  void intersect_coherent(const ray*, size_t count, std::optional<hit>* out) const override {
    streams.push_back(count);
    for (size_t i = 0; i < count; ++i) {
      out[i] = hit{};
      out[i]->t = float(++queries);
    }
  }
  bool occluded(const ray&) const override { return false; }
  mutable size_t queries = 0, single = 0;
  mutable std::vector<size_t> streams;
};

bool same_bits(const ray& a, const ray& b) {
  return std::memcmp(&a.origin, &b.origin, sizeof(a.origin)) == 0 &&
         std::memcmp(&a.direction, &b.direction, sizeof(a.direction)) == 0;
}

view_camera camera() { return make_look_at_camera(dvec3(0, 0, 3), dvec3(0.0), dvec3(0, 1, 0), 40.0, 64, 48); }

TEST(camera_rays, each_sample_has_the_ray_its_pixel_and_index_seed_and_its_hit) {
  const view_camera cam = camera();
  render_settings settings;
  settings.samples_per_pixel = 3;
  recording_accelerator accel;
  camera_ray_batch b = tile_camera_rays(10, 20, 15, 23);
  size_t expected_t = 0;
  for (int y = 20; y < 23; ++y)
    for (int x = 10; x < 15; ++x)
      for (int s = 0; s < 3; ++s) {
        const size_t k = camera_ray_at(b, x, y, s, cam, settings, accel);
        const camera_ray_source& src = b.sources[k];
        EXPECT_EQ(src.x, x);
        EXPECT_EQ(src.y, y);
        EXPECT_EQ(src.sample, uint32_t(s));
        const vec2 offset = pixel_sample_offset(false, uint32_t(x), uint32_t(y), uint32_t(s), 3);
        EXPECT_EQ(src.offset, offset);
        EXPECT_TRUE(
            same_bits(b.rays[k], generate_camera_ray(cam, x + double(offset.x), y + double(offset.y))));
        EXPECT_EQ(src.cone.spread, sample_cone(cam, 3).spread);
        EXPECT_EQ(src.time, 0.0f);
        ASSERT_TRUE(b.hits[k].has_value());
        EXPECT_EQ(b.hits[k]->t, float(++expected_t));  // traced once each, in shading order
      }
  EXPECT_EQ(accel.queries, size_t(5 * 3 * 3));
  EXPECT_TRUE(accel.streams.empty());  // packets off: one ray at a time
}

TEST(camera_rays, with_packets_the_streams_are_runs_of_whole_rows) {
  const view_camera cam = camera();
  render_settings settings;
  settings.packets = true;
  settings.samples_per_pixel = 16;  // 32 pixels × 16 = 512 a row: two rows a stream
  recording_accelerator accel;
  camera_ray_batch b = tile_camera_rays(0, 0, 32, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 32; ++x)
      for (int s = 0; s < 16; ++s) camera_ray_at(b, x, y, s, cam, settings, accel);
  EXPECT_EQ(accel.streams, (std::vector<size_t>{1024, 1024, 512}));
  EXPECT_EQ(accel.single, 0u);
}

TEST(camera_rays, rows_longer_than_a_stream_are_traced_one_ray_at_a_time) {
  const view_camera cam = camera();
  render_settings settings;
  settings.packets = true;
  settings.samples_per_pixel = 40;  // 32 × 40 = 1280 a row, more than max_rays
  recording_accelerator accel;
  camera_ray_batch b = tile_camera_rays(0, 0, 32, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 32; ++x)
      for (int s = 0; s < 40; ++s) {
        const size_t k = camera_ray_at(b, x, y, s, cam, settings, accel);
        ASSERT_EQ(b.sources[k].x, x);
        ASSERT_EQ(b.sources[k].sample, uint32_t(s));
      }
  EXPECT_TRUE(accel.streams.empty());
  EXPECT_EQ(accel.single, size_t(2 * 1280));
}

TEST(camera_rays, a_sample_asked_for_out_of_order_is_made_where_it_is_asked) {
  const view_camera cam = camera();
  render_settings settings;
  settings.samples_per_pixel = 4;
  recording_accelerator accel;
  camera_ray_batch b = tile_camera_rays(0, 0, 8, 8);
  const size_t k = camera_ray_at(b, 6, 5, 2, cam, settings, accel);
  EXPECT_EQ(b.sources[k].x, 6);
  EXPECT_EQ(b.sources[k].y, 5);
  EXPECT_EQ(b.sources[k].sample, 2u);
  const size_t back = camera_ray_at(b, 1, 0, 3, cam, settings, accel);  // an earlier row: made again
  EXPECT_EQ(b.sources[back].x, 1);
  EXPECT_EQ(b.sources[back].y, 0);
}

}  // namespace
}  // namespace kiln
