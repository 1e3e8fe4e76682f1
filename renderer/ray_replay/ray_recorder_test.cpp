#include "ray_replay/ray_recorder.h"

#include <gtest/gtest.h>

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/synthetic_scenes.h"
#include "ray_replay/bench_run.h"

namespace kiln {
namespace {

// A sphere lit by one point light: camera rays, shadow rays and no secondary rays.
scene lit_sphere() {
  scene s = scene_from_mesh(make_sphere_mesh(20, 40, 1.0f));
  s.materials[0].metallic_factor = 0.0f;
  light l;
  l.position = dvec3(2, 3, 4);
  l.intensity = 20.0f;
  s.lights.push_back(l);
  return s;
}

TEST(ray_recorder, records_exactly_the_rays_the_render_counts) {
  scene s = lit_sphere();
  embree_accelerator embree(s);
  ray_recorder recorder(embree);
  view_camera cam = make_look_at_camera(dvec3(0, 0, 4), dvec3(0), dvec3(0, 1, 0), 40.0, 40, 30);
  render_settings settings;
  settings.threads = 3;
  render_statistics stats;
  render_image(s, recorder, cam, settings, &stats);
  const recorded_rays rays = recorder.rays();
  EXPECT_EQ(rays.intersect[size_t(ray_kind::camera)].size(), stats.rays.camera);
  EXPECT_EQ(rays.occluded[size_t(ray_kind::shadow)].size(), stats.rays.shadow);
  EXPECT_EQ(stats.rays.camera, 40u * 30u);
  EXPECT_GT(stats.rays.shadow, 100u);  // the sphere covers a good part of the frame
  EXPECT_EQ(rays.total(), stats.rays.camera + stats.rays.shadow);
}

TEST(ray_recorder, bare_embree_loop_agrees_with_kiln_queries) {
  scene s = lit_sphere();
  embree_accelerator embree(s);
  ray_recorder recorder(embree);
  view_camera cam = make_look_at_camera(dvec3(0, 0, 4), dvec3(0), dvec3(0, 1, 0), 40.0, 40, 30);
  render_image(s, recorder, cam, render_settings{});
  const recorded_rays rays = recorder.rays();
  for (bool occlusion : {false, true}) {
    const std::vector<ray>& set =
        occlusion ? rays.occluded[size_t(ray_kind::shadow)] : rays.intersect[size_t(ray_kind::camera)];
    size_t kiln_hits = 0;
    for (const ray& r : set) kiln_hits += occlusion ? embree.occluded(r) : embree.intersect(r).has_value();
    EXPECT_EQ(embree.trace_bare(set.data(), set.size(), occlusion), kiln_hits) << occlusion;
    if (!occlusion) {
      EXPECT_GT(kiln_hits, 200u);
    }
  }
}

TEST(ray_recorder, records_a_batch_and_answers_it_with_the_inner_batch) {
  const scene s = lit_sphere();
  const embree_accelerator embree(s);
  const ray_recorder recorder(embree);
  std::vector<ray> rays;
  for (int i = 0; i < 37; ++i) {
    ray r;
    r.origin = vec3(-3.0f, 0.05f * float(i) - 0.9f, 0.0f);
    r.direction = vec3(1.0f, 0.0f, 0.0f);
    r.kind = i % 2 ? ray_kind::shadow : ray_kind::reflection;
    rays.push_back(r);
  }
  std::vector<uint8_t> blocked(rays.size());
  recorder.occluded_batch(rays.data(), rays.size(), blocked.data());
  const recorded_rays recorded = recorder.rays();
  EXPECT_EQ(recorded.occluded[size_t(ray_kind::shadow)].size(), 18u);
  EXPECT_EQ(recorded.occluded[size_t(ray_kind::reflection)].size(), 19u);
  EXPECT_EQ(recorded.total(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(blocked[i], embree.occluded(rays[i])) << i;
  EXPECT_EQ(std::count(blocked.begin(), blocked.end(), uint8_t(1)), 37);  // all cross the unit sphere
}

TEST(bench_run, reports_rays_by_kind_and_both_loops_see_the_same_hits) {
  scene s = lit_sphere();
  view_camera cam = make_look_at_camera(dvec3(0, 0, 4), dvec3(0), dvec3(0, 1, 0), 40.0, 32, 24);
  render_settings render;
  render.threads = 2;
  bench_settings settings;
  settings.repeats = 1;
  for (const char* accel : {"embree", "grid"}) {
    settings.accel = accel;
    bench_measurement m = run_bench(s, cam, render, settings);
    EXPECT_EQ(m.rays.camera, 32u * 24u) << accel;
    EXPECT_EQ(m.unique_triangles, s.meshes[0].triangle_count());
    EXPECT_EQ(m.placed_triangles, m.unique_triangles);
    EXPECT_GT(m.peak_rss_after_render, 0u);
    ASSERT_EQ(m.kinds.size(), 2u) << accel;  // camera (intersect) and shadow (occluded)
    for (const kind_measurement& k : m.kinds) {
      EXPECT_EQ(k.bare_hits, k.kiln_hits) << accel << " " << k.kind;
      EXPECT_GT(k.bare_seconds, 0.0);
      EXPECT_GT(k.kiln_seconds, 0.0);
    }
    EXPECT_EQ(m.kinds[0].kind, "camera");
    EXPECT_EQ(m.kinds[0].rays, m.rays.camera);
    EXPECT_EQ(m.kinds[1].kind, "shadow");
    EXPECT_EQ(m.kinds[1].rays, m.rays.shadow);
    // Occlusion queries are also timed through occluded_batch, with the same answers.
    EXPECT_GT(m.kinds[1].kiln_batch_seconds, 0.0);
    EXPECT_EQ(m.kinds[1].kiln_batch_hits, m.kinds[1].kiln_hits);
    EXPECT_EQ(m.kinds[0].kiln_batch_seconds, 0.0);
    EXPECT_FALSE(m.kinds[1].replayed_as_occlusion);
  }
}

TEST(bench_run, walked_shadow_rays_are_also_timed_as_occlusion_queries) {
  // Half-transparent spheres that shade each other: the reference render walks its shadow rays with
  // closest-hit queries, and the bench asks the same rays occlusion queries in a row of their own,
  // outside the render's totals.
  scene s = make_instanced_scene(make_sphere_mesh(20, 40, 1.0f), 3, 5);
  s.materials[0].alpha = alpha_mode::blend;
  s.materials[0].base_color_factor.a = 0.5f;
  const bounds3 b = world_bounds(s);
  const double size = glm::length(b.diagonal());
  light l;
  l.position = b.center() + dvec3(0.6 * size);
  l.intensity = 20.0f;
  s.lights.push_back(l);
  view_camera cam =
      make_look_at_camera(b.center() + dvec3(0.0, 0.0, 1.5 * size), b.center(), dvec3(0, 1, 0), 40.0, 32, 24);
  render_settings render;
  render.threads = 2;
  // The wave asks its camera hits' shadow rays as occlusion batches before it walks any, and those
  // are timed as what they are; the reference walks every one.
  render.reference_shading = true;
  bench_settings settings;
  settings.repeats = 1;
  const bench_measurement m = run_bench(s, cam, render, settings);
  const kind_measurement* walked = nullptr;
  const kind_measurement* replayed = nullptr;
  for (const kind_measurement& k : m.kinds) {
    if (k.kind == "shadow" && k.query == "intersect") walked = &k;
    if (k.kind == "shadow" && k.query == "occluded") replayed = &k;
  }
  ASSERT_TRUE(walked && replayed);
  EXPECT_FALSE(walked->replayed_as_occlusion);
  EXPECT_TRUE(replayed->replayed_as_occlusion);
  EXPECT_EQ(replayed->rays, walked->rays);
  EXPECT_EQ(replayed->kiln_hits, walked->kiln_hits);  // blocked exactly when the walk's query hits
  EXPECT_EQ(replayed->kiln_batch_hits, replayed->kiln_hits);
  EXPECT_GT(replayed->kiln_hits, 0u);
}

}  // namespace
}  // namespace kiln
