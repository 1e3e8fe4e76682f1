// A camera sample's ray tree is bounded: 40 nested glass boxes under --max-depth 64 and
// --min-throughput 0 double the rays at every surface (2^64 of them), so a sample spawns at most
// max_rays_per_sample reflected, refracted and continued rays, and a cancel raised while one such
// sample runs is seen inside its tree within a bounded number of rays. Counts rays, never time.
#include <gtest/gtest.h>

#include <atomic>

#include "accel/embree/embree_accelerator.h"
#include "core/error.h"
#include "render/tile_renderer.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

constexpr int box_count = 40;

// Smooth glass boxes nested around the origin, half-sizes 1 to box_count, and no light (so no
// shadow rays: every closest-hit query is a camera, reflected or refracted ray).
scene nested_glass() {
  scene s;
  material glass;
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission_factor = 1.0f;
  glass.ior = 1.5f;
  glass.thickness_factor = 1.0f;
  s.materials = {glass};
  for (int i = 1; i <= box_count; ++i) testing::add_box(s, vec3(-float(i)), vec3(float(i)), 0);
  return s;
}

// Counts closest-hit queries; after raise_at of them it raises a cancel flag (when given), and after
// give_up_at it answers every query with a miss, so that a tree that ignores the cancel still ends
// (it then fails the test's count instead of running for hours).
class counting_accelerator final : public accelerator {
 public:
  counting_accelerator(const accelerator& inner, uint64_t raise_at, uint64_t give_up_at,
                       std::atomic<bool>* cancel)
      : inner_(inner), raise_at_(raise_at), give_up_at_(give_up_at), cancel_(cancel) {}
  std::optional<hit> intersect(const ray& r) const override {
    const uint64_t n = ++queries;
    if (cancel_ && n == raise_at_) cancel_->store(true);
    if (n > give_up_at_) return std::nullopt;
    return inner_.intersect(r);
  }
  bool occluded(const ray& r) const override { return inner_.occluded(r); }
  mutable std::atomic<uint64_t> queries{0};

 private:
  const accelerator& inner_;
  uint64_t raise_at_, give_up_at_;
  std::atomic<bool>* cancel_;
};

// One camera sample (1×1 image, 1 spp) straight at the boxes' centre, one thread.
render_settings deep_glass_settings() {
  render_settings settings;
  settings.threads = 1;
  settings.shading.max_depth = 64;
  settings.shading.min_throughput = 0.0f;
  return settings;
}

view_camera one_pixel_camera() {
  return make_look_at_camera(dvec3(0, 0, 100), dvec3(0.0), dvec3(0, 1, 0), 10.0, 1, 1);
}

TEST(ray_budget, a_sample_spawns_at_most_max_rays_per_sample_secondary_rays) {
  const scene s = nested_glass();
  embree_accelerator embree(s);
  for (uint64_t budget : {1u, 100u, 5000u}) {
    counting_accelerator accel(embree, 0, 1000000, nullptr);
    render_settings settings = deep_glass_settings();
    settings.shading.max_rays_per_sample = budget;
    render_statistics stats;
    render_image(s, accel, one_pixel_camera(), settings, &stats);
    const uint64_t spawned = stats.rays.reflection + stats.rays.refraction + stats.rays.transparency;
    // The tree is far larger than any budget: each one is spent exactly, and every spawned ray is
    // one closest-hit query beside the camera ray's.
    EXPECT_EQ(spawned, budget);
    EXPECT_EQ(accel.queries.load(), 1 + budget);
    EXPECT_EQ(stats.rays.camera, 1u);
  }
}

TEST(ray_budget, the_default_budget_leaves_trees_of_depth_eleven_whole) {
  // 2^12 − 2 rays below a camera ray at depth 11: within the default 4096.
  EXPECT_GE(shading_options{}.max_rays_per_sample, (uint64_t(1) << 12) - 2);
}

TEST(ray_budget, a_cancel_raised_inside_one_sample_stops_its_tree_within_a_bounded_number_of_rays) {
  const scene s = nested_glass();
  embree_accelerator embree(s);
  constexpr uint64_t raise_at = 1000;
  constexpr uint64_t give_up_at = raise_at + 1000000;
  std::atomic<bool> cancel{false};
  counting_accelerator accel(embree, raise_at, give_up_at, &cancel);
  render_settings settings = deep_glass_settings();
  settings.shading.max_rays_per_sample = ~uint64_t(0);  // no budget: only the cancel can stop it
  settings.cancel = &cancel;
  try {
    render_image(s, accel, one_pixel_camera(), settings);
    ADD_FAILURE() << "the render was not interrupted";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::interrupted);
  }
  // Seen within one polling interval of spawned rays; the branches already on the stack (at most
  // one per depth level) then spawn nothing more.
  EXPECT_LE(accel.queries.load(), raise_at + 2 * ray_budget::poll_interval + 64);
}

}  // namespace
}  // namespace kiln
