// Whitted's mirror for metals through the real shading code and the Embree backend: a smooth metal
// reflects its base colour times the mirrored radiance at normal incidence (Schlick's F0), the
// depth limit and the throughput cutoff stop the recursion exactly where they say, and roughness
// fades the mirror term out.
#include <gtest/gtest.h>

#include "accel/embree/embree_accelerator.h"
#include "shade/whitted.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

using testing::add_quad;
using testing::make_ray;

material metal(float base, float roughness) {
  material m;
  m.base_color_factor = vec4(base, base, base, 1.0f);
  m.metallic_factor = 1.0f;
  m.roughness_factor = roughness;
  return m;
}

// An emitting ceiling, seen from below.
material ceiling(float radiance) {
  material m = testing::emitter(radiance);
  m.double_sided = true;
  return m;
}

// A metal floor at z = 0 and a large emitting ceiling at z = 2; no lights, so the only light a
// ray down onto the floor brings back is the mirrored ceiling.
scene floor_under_emitter(float base, float roughness) {
  scene s;
  s.materials = {metal(base, roughness), ceiling(3.0f)};
  add_quad(s, -50, -50, 50, 50, 0.0f, 0);
  add_quad(s, -50, -50, 50, 50, 2.0f, 1);
  return s;
}

vec3 trace_down(const scene& s, const shading_options& options, ray_counts& counts) {
  embree_accelerator accel(s);
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  return trace_radiance(ctx, make_ray(vec3(0.3f, -0.2f, 1.0f), vec3(0, 0, -1)), path_state{}, counts);
}

TEST(mirror, smooth_metal_reflects_base_colour_times_the_mirrored_radiance) {
  scene s = floor_under_emitter(0.5f, 0.0f);
  shading_options options;
  ray_counts counts;
  vec3 radiance = trace_down(s, options, counts);
  // Head-on, Schlick's Fresnel of a metal is its base colour: 0.5 × 3.
  EXPECT_NEAR(radiance.x, 1.5f, 1e-5f);
  EXPECT_NEAR(radiance.z, 1.5f, 1e-5f);
  EXPECT_EQ(counts.reflection, 1u);  // the ceiling is not a mirror, so the recursion ends there
}

TEST(mirror, depth_limit_zero_traces_no_reflection) {
  scene s = floor_under_emitter(0.5f, 0.0f);
  shading_options options;
  options.max_depth = 0;
  ray_counts counts;
  EXPECT_EQ(trace_down(s, options, counts), vec3(0.0f));
  EXPECT_EQ(counts.reflection, 0u);
}

TEST(mirror, throughput_cutoff_drops_reflections_weighted_below_it) {
  scene s = floor_under_emitter(0.5f, 0.0f);
  shading_options options;
  options.min_throughput = 0.6f;  // the reflection carries 0.5
  ray_counts counts;
  EXPECT_EQ(trace_down(s, options, counts), vec3(0.0f));
  EXPECT_EQ(counts.reflection, 0u);
}

TEST(mirror, roughness_fades_the_mirror_term_linearly_to_nothing) {
  shading_options options;  // fades out at roughness 0.25
  ray_counts counts;
  vec3 half = trace_down(floor_under_emitter(0.5f, 0.125f), options, counts);
  EXPECT_NEAR(half.x, 0.75f, 1e-5f);
  vec3 rough = trace_down(floor_under_emitter(0.5f, 0.3f), options, counts);
  EXPECT_EQ(rough, vec3(0.0f));
}

TEST(mirror, two_parallel_mirrors_bounce_exactly_max_depth_times) {
  scene s;
  s.materials = {metal(1.0f, 0.0f)};
  add_quad(s, -1e4f, -1e4f, 1e4f, 1e4f, 0.0f, 0);
  add_quad(s, -1e4f, -1e4f, 1e4f, 1e4f, 1.0f, 0);
  s.materials[0].double_sided = true;
  embree_accelerator accel(s);
  for (int depth : {1, 5, 12}) {
    shading_options options;
    options.max_depth = depth;
    shading_context ctx{s, accel, options, scene_has_see_through(s)};
    ray_counts counts;
    trace_radiance(ctx, make_ray(vec3(0, 0, 0.5f), vec3(0.3f, 0.1f, -1.0f)), path_state{}, counts);
    EXPECT_EQ(counts.reflection, uint64_t(depth)) << depth;
  }
}

}  // namespace
}  // namespace kiln
