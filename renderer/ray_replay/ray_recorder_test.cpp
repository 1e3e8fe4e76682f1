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
  }
}

}  // namespace
}  // namespace kiln
