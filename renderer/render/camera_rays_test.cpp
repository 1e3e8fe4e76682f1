// The camera-ray stage: every sample of a tile gets the ray its pixel and index seed, with where it
// comes from and the backend's hit for it; with packets each stream is one pixel's samples (at most
// max_rays of them, from its first or a multiple of max_rays), whatever the tile, and a pixel of one
// sample is one ray.
#include "render/camera_rays.h"

#include <gtest/gtest.h>

#include <array>
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
  void intersect_coherent(const ray* rays, size_t count, std::optional<hit>* out) const override {
    streams.push_back(count);
    stream_rays.emplace_back(rays, rays + count);
    for (size_t i = 0; i < count; ++i) {
      out[i] = hit{};
      out[i]->t = float(++queries);
    }
  }
  bool occluded(const ray&) const override { return false; }
  mutable size_t queries = 0, single = 0;
  mutable std::vector<size_t> streams;
  mutable std::vector<std::vector<ray>> stream_rays;
};

bool same_bits(const ray& a, const ray& b) {
  return std::memcmp(&a.origin, &b.origin, sizeof(a.origin)) == 0 &&
         std::memcmp(&a.direction, &b.direction, sizeof(a.direction)) == 0;
}

view_camera camera() { return make_look_at_camera(dvec3(0, 0, 3), dvec3(0.0), dvec3(0, 1, 0), 40.0, 64, 48); }

TEST(camera_rays, each_sample_has_the_ray_its_pixel_and_index_seed_and_its_hit) {
  const view_camera cam = camera();
  render_settings settings;
  settings.packets = false;
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

// The rays of pixel (x, y)'s samples [first, first + count), as the stage makes them.
std::vector<ray> pixel_rays(const view_camera& cam, int spp, int x, int y, int first, int count) {
  std::vector<ray> out;
  for (int s = first; s < first + count; ++s) {
    const vec2 offset = pixel_sample_offset(false, uint32_t(x), uint32_t(y), uint32_t(s), uint32_t(spp));
    out.push_back(generate_camera_ray(cam, x + double(offset.x), y + double(offset.y)));
  }
  return out;
}

bool same_rays(const std::vector<ray>& a, const std::vector<ray>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!same_bits(a[i], b[i])) return false;
  return true;
}

// Every pixel of the tile [x0, x1) × [y0, y1) asked for in shading order; the streams the stage sent.
recording_accelerator traced_tile(int x0, int y0, int x1, int y1, int spp) {
  render_settings settings;
  settings.samples_per_pixel = spp;
  recording_accelerator accel;
  camera_ray_batch b = tile_camera_rays(x0, y0, x1, y1);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int s = 0; s < spp; ++s) {
        const size_t k = camera_ray_at(b, x, y, s, camera(), settings, accel);
        EXPECT_EQ(b.sources[k].x, x);
        EXPECT_EQ(b.sources[k].sample, uint32_t(s));
      }
  return accel;
}

TEST(camera_rays, packets_are_on_by_default_and_each_stream_is_one_pixel_s_samples) {
  EXPECT_TRUE(render_settings{}.packets);
  const recording_accelerator accel = traced_tile(0, 0, 32, 5, 16);
  ASSERT_EQ(accel.streams.size(), size_t(32 * 5));
  EXPECT_EQ(accel.single, 0u);
  size_t k = 0;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 32; ++x)
      EXPECT_TRUE(same_rays(accel.stream_rays[k++], pixel_rays(camera(), 16, x, y, 0, 16)));
}

TEST(camera_rays, a_pixel_s_stream_is_the_same_whatever_tile_holds_it) {
  // Pixel (13, 7) at 40 spp in a 32-wide tile (rows of 1280 samples, more than a run) and in a
  // 5-wide tile at another offset (rows of 200): the same one stream of its 40 samples.
  const std::vector<ray> expected = pixel_rays(camera(), 40, 13, 7, 0, 40);
  for (const auto& tile : {std::array<int, 4>{0, 0, 32, 9}, std::array<int, 4>{11, 6, 16, 8}}) {
    const recording_accelerator accel = traced_tile(tile[0], tile[1], tile[2], tile[3], 40);
    EXPECT_EQ(accel.single, 0u);
    size_t holding = 0;
    for (const std::vector<ray>& stream : accel.stream_rays) holding += same_rays(stream, expected);
    EXPECT_EQ(holding, 1u);
  }
}

TEST(camera_rays, a_pixel_of_more_samples_than_a_run_streams_them_from_its_first_in_runs) {
  const recording_accelerator accel = traced_tile(3, 2, 5, 3, 1500);
  EXPECT_EQ(accel.streams, (std::vector<size_t>{1024, 476, 1024, 476}));
  EXPECT_TRUE(same_rays(accel.stream_rays[1], pixel_rays(camera(), 1500, 3, 2, 1024, 476)));
  EXPECT_TRUE(same_rays(accel.stream_rays[2], pixel_rays(camera(), 1500, 4, 2, 0, 1024)));
}

TEST(camera_rays, a_pixel_of_one_sample_is_one_ray) {
  const recording_accelerator accel = traced_tile(0, 0, 16, 4, 1);
  EXPECT_TRUE(accel.streams.empty());
  EXPECT_EQ(accel.single, size_t(16 * 4));
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
