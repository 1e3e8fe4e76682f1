// The wave answers the shadow rays of a run of camera hits together: every camera hit's shadow rays
// (a point light's and the environment's) reach the accelerator through occluded_batch, many at a
// time, and the image equals the reference shading's (each shadow ray asked alone) bit for bit,
// with the passes, light groups and shadow mattes that file the light by source too. With a
// see-through blocker the batches first find what stops light and what is clear, and only the rays
// that cross the see-through surface are walked for their transmittance.
#include <gtest/gtest.h>

#include <atomic>

#include "accel/embree/embree_accelerator.h"
#include "render/tile_renderer.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

// Counts single occlusion queries and occlusion batches (and the rays in them), answering both
// through the inner accelerator's own kinds.
class occlusion_counter final : public accelerator {
 public:
  explicit occlusion_counter(const accelerator& inner) : inner_(inner) {}
  std::optional<hit> intersect(const ray& r) const override { return inner_.intersect(r); }
  std::optional<hit> intersect_for_shadow(const ray& r) const override {
    return inner_.intersect_for_shadow(r);
  }
  bool occluded(const ray& r) const override {
    ++single;
    return inner_.occluded(r);
  }
  void occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const override {
    ++batches;
    batched += count;
    inner_.occluded_batch(rays, count, blocked);
  }
  mutable std::atomic<uint64_t> single{0}, batches{0}, batched{0};

 private:
  const accelerator& inner_;
};

// A floor under a box that shadows it, a point light above and a grey sky that lights too; glass:
// the box lets light through (transmission), so blocked shadow rays are walked.
scene shadowed_floor(bool glass) {
  scene s;
  material floor;
  floor.base_color_factor = vec4(0.8f, 0.7f, 0.6f, 1.0f);
  floor.metallic_factor = 0.0f;
  floor.roughness_factor = 0.6f;
  material box = floor;
  box.base_color_factor = vec4(0.3f, 0.5f, 0.9f, 1.0f);
  if (glass) {
    box.transmission_factor = 1.0f;
    box.roughness_factor = 0.0f;
  }
  s.materials = {floor, box};
  testing::add_quad(s, -4.0f, -4.0f, 4.0f, 4.0f, 0.0f, 0);
  testing::add_box(s, vec3(-1.0f, -1.0f, 0.0f), vec3(1.0f, 1.0f, 1.5f), 1);
  light l;
  l.position = dvec3(1.5, 2.0, 5.0);
  l.intensity = 40.0f;
  s.lights.push_back(l);
  s.env.color = vec3(0.4f, 0.45f, 0.5f);
  return s;
}

view_camera floor_camera() {
  return make_look_at_camera(dvec3(0.0, -7.0, 6.0), dvec3(0.0), dvec3(0, 0, 1), 50.0, 24, 16);
}

render_settings settings_for(bool reference, bool with_passes) {
  render_settings settings;
  settings.threads = 1;
  settings.samples_per_pixel = 4;
  settings.shading.max_depth = 0;  // camera hits only: every shadow ray is a camera hit's
  settings.reference_shading = reference;
  if (with_passes) {
    for (aov a : {aov::light_groups, aov::diffuse, aov::specular, aov::shadow}) settings.aovs.set(a);
  }
  return settings;
}

void expect_same_bits(const film& a, const film& b) {
  ASSERT_EQ(a.color.size(), b.color.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.color.size(); ++i) differing += a.color[i] != b.color[i];
  EXPECT_EQ(differing, 0u);
  ASSERT_EQ(a.light_groups.size(), b.light_groups.size());
  for (size_t i = 0; i < a.light_groups.size(); ++i) EXPECT_EQ(a.light_groups[i], b.light_groups[i]) << i;
  EXPECT_EQ(a.shadow, b.shadow);
  EXPECT_EQ(a.vec3_layer(aov::diffuse), b.vec3_layer(aov::diffuse));
}

TEST(wave_shadow, camera_hits_ask_their_shadow_rays_in_batches_and_match_the_reference) {
  for (bool glass : {false, true}) {
    for (bool with_passes : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "glass " << glass << ", passes " << with_passes);
      const scene s = shadowed_floor(glass);
      embree_accelerator embree(s);
      occlusion_counter wave_accel(embree), reference_accel(embree);
      render_statistics wave_stats, reference_stats;
      const film wave =
          render_image(s, wave_accel, floor_camera(), settings_for(false, with_passes), &wave_stats);
      const film reference =
          render_image(s, reference_accel, floor_camera(), settings_for(true, with_passes), &reference_stats);
      expect_same_bits(wave, reference);
      // The reference asks each ray alone (through the walk when something lets light through).
      EXPECT_EQ(reference_accel.batches.load(), 0u);
      EXPECT_GT(reference_stats.rays.shadow, 1000u);
      // The wave asks no shadow ray alone; its batches hold a run's camera hits (24×16 pixels at 4
      // spp: two runs), each with the light's ray and the sky's.
      EXPECT_EQ(wave_accel.single.load(), 0u);
      EXPECT_GE(wave_accel.batches.load(), 1u);
      EXPECT_GE(wave_accel.batched.load() / wave_accel.batches.load(), 500u);
      if (!glass) {
        EXPECT_EQ(reference_accel.single.load(), wave_accel.batched.load());
        EXPECT_EQ(wave_stats.rays.shadow, reference_stats.rays.shadow);
        continue;
      }
      // Glass: the batches (what stops light, then what lets it through) leave only the rays that
      // cross the glass box to be walked, far fewer queries than the reference's walk of every ray.
      const uint64_t walked = wave_stats.rays.shadow - wave_accel.batched.load();
      EXPECT_GT(walked, 0u);
      EXPECT_LT(walked, reference_stats.rays.shadow / 2);
    }
  }
}

}  // namespace
}  // namespace kiln
