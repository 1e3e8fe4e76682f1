// glTF alpha and sidedness through the real shading code and the Embree backend: alphaMode MASK
// removes texels below the cutoff from both closest-hit and occlusion queries (the Embree filter
// functions), BLEND composites alpha·surface + (1 - alpha)·behind and lets (1 - alpha) of the light
// through to shadows, and doubleSided false culls back faces for camera and secondary rays.
#include <gtest/gtest.h>

#include "accel/embree/embree_accelerator.h"
#include "scene/alpha_coverage.h"
#include "shade/whitted.h"
#include "support/shadow_probe.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

using testing::add_box;
using testing::add_quad;
using testing::make_ray;

material emitter(float radiance, float alpha = 1.0f) {
  material m;
  m.base_color_factor = vec4(0.0f, 0.0f, 0.0f, alpha);
  m.metallic_factor = 0.0f;
  m.specular_factor = 0.0f;
  m.emissive_factor = vec3(radiance);
  return m;
}

material diffuse() {
  material m;
  m.metallic_factor = 0.0f;
  m.specular_factor = 0.0f;
  return m;
}

// A 2x1 white texture: the left texel has alpha 0, the right one alpha 1 (nearest, clamped).
void add_half_transparent_texture(scene& s) {
  image img;
  img.width = 2;
  img.height = 1;
  img.texels8 = {255, 255, 255, 0, 255, 255, 255, 255};
  s.images.push_back(img);
  texture tex;
  tex.sampling = {wrap_mode::clamp_to_edge, wrap_mode::clamp_to_edge, filter_mode::nearest};
  s.textures.push_back(tex);
}

TEST(alpha, mask_removes_texels_below_the_cutoff_from_hits_and_shadows) {
  scene s;
  add_half_transparent_texture(s);
  material cutout = diffuse();
  cutout.alpha = alpha_mode::mask;
  cutout.alpha_cutoff = 0.5f;
  cutout.base_color_texture.texture = 0;
  s.materials = {diffuse(), cutout};
  add_box(s, vec3(-5, -5, -1), vec3(5, 5, 0), 0);
  add_quad(s, -1, -1, 1, 1, 1, 1);
  embree_accelerator accel(s);

  // Left half: alpha 0, not there. Right half: alpha 1, hit at t = 1.
  std::optional<hit> left = accel.intersect(make_ray(vec3(-0.5f, 0.2f, 2), vec3(0, 0, -1)));
  std::optional<hit> right = accel.intersect(make_ray(vec3(0.5f, 0.2f, 2), vec3(0, 0, -1)));
  ASSERT_TRUE(left && right);
  EXPECT_EQ(left->instance_id, 0u);
  EXPECT_NEAR(left->t, 2.0f, 1e-5f);
  EXPECT_EQ(right->instance_id, 1u);
  EXPECT_NEAR(right->t, 1.0f, 1e-5f);
  EXPECT_EQ(alpha_at(s, 1, right->primitive_id, right->u, right->v), 1.0f);

  // Shadow rays from the floor straight up: blocked only under the opaque half.
  ray up_left = make_ray(vec3(-0.5f, 0.2f, 0.01f), vec3(0, 0, 1));
  ray up_right = make_ray(vec3(0.5f, 0.2f, 0.01f), vec3(0, 0, 1));
  EXPECT_FALSE(accel.occluded(up_left));
  EXPECT_TRUE(accel.occluded(up_right));

  // The same texels with alphaMode OPAQUE are solid everywhere (no filter is installed).
  s.materials[1].alpha = alpha_mode::opaque;
  embree_accelerator opaque(s);
  EXPECT_TRUE(opaque.occluded(up_left));
}

TEST(alpha, blend_composites_the_surface_over_what_is_behind_it) {
  const float front = 4.0f, back = 1.0f, alpha = 0.25f;
  scene s;
  material glaze = emitter(front, alpha);
  glaze.alpha = alpha_mode::blend;
  s.materials = {emitter(back), glaze};
  add_box(s, vec3(-5, -5, -1), vec3(5, 5, 0), 0);
  add_quad(s, -1, -1, 1, 1, 1, 1);
  embree_accelerator accel(s);
  shading_options options;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  vec3 seen = trace_radiance(ctx, make_ray(vec3(0.3f, 0.1f, 3), vec3(0, 0, -1)), path_state{}, counts);
  EXPECT_NEAR(seen.x, alpha * front + (1 - alpha) * back, 1e-5f);
  EXPECT_EQ(counts.transparency, 1u);
}

TEST(alpha, blend_surface_passes_the_uncovered_share_of_light_to_shadows) {
  scene s;
  material glaze = diffuse();
  glaze.base_color_factor.a = 0.25f;
  glaze.alpha = alpha_mode::blend;
  s.materials = {diffuse(), glaze};
  add_quad(s, 0, -10, 10, 10, 1, 1);
  EXPECT_NEAR(testing::light_through_cover(s).x, 0.75f, 1e-5f);
}

TEST(alpha, single_sided_back_faces_are_culled_double_sided_ones_are_not) {
  scene s;
  s.materials = {emitter(2.0f)};
  s.env.color = vec3(0.5f);
  add_quad(s, -1, -1, 1, 1, 0, 0);  // faces +z
  embree_accelerator accel(s);
  shading_options options;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  ray from_above = make_ray(vec3(0, 0, 1), vec3(0, 0, -1));
  ray from_below = make_ray(vec3(0, 0, -1), vec3(0, 0, 1));
  EXPECT_EQ(trace_radiance(ctx, from_above, path_state{}, counts).x, 2.0f);
  EXPECT_EQ(trace_radiance(ctx, from_below, path_state{}, counts).x, 0.5f);  // culled: the environment
  EXPECT_TRUE(accel.occluded(from_below));  // still casts a shadow from behind
  s.materials[0].double_sided = true;
  EXPECT_EQ(trace_radiance(ctx, from_below, path_state{}, counts).x, 2.0f);
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

TEST(unlit, radiance_is_the_base_colour_whatever_the_lights) {
  scene s;
  material flat;
  flat.unlit = true;
  flat.base_color_factor = vec4(0.2f, 0.4f, 0.8f, 1.0f);
  flat.metallic_factor = 1.0f;
  flat.roughness_factor = 0.0f;  // a lit material this smooth would mirror the environment
  s.materials = {flat};
  s.env.color = vec3(5.0f);
  testing::add_quad(s, -1, -1, 1, 1, 0, 0);
  light l;
  l.position = dvec3(0, 0, 2);
  l.intensity = 100.0f;
  s.lights.push_back(l);
  embree_accelerator accel(s);
  shading_options options;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  vec3 seen =
      trace_radiance(ctx, testing::make_ray(vec3(0.1f, 0.2f, 1), vec3(0, 0, -1)), path_state{}, counts);
  EXPECT_EQ(seen, vec3(0.2f, 0.4f, 0.8f));
  EXPECT_EQ(counts.shadow + counts.reflection, 0u);
}

}  // namespace
}  // namespace kiln
