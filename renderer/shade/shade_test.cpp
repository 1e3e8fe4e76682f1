#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "geometry/quadric.h"
#include "geometry/triangle.h"
#include "shade/dielectric.h"
#include "shade/lights.h"
#include "shade/material_eval.h"
#include "shade/material_lobes.h"
#include "shade/ray_cone.h"
#include "shade/surface.h"
#include "shade/texture_sampling.h"

namespace kiln {
namespace {

scene one_triangle(const dmat4& world_from_object) {
  scene s;
  mesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}};
  m.indices = {0, 1, 2};
  m.normals = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
  m.texcoords0 = {{0, 0}, {1, 0}, {0, 1}};
  s.meshes.push_back(m);
  s.materials.emplace_back();
  instance inst;
  inst.world_from_object = world_from_object;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
  return s;
}

// The constants a hit reads from its instance (error bounds, tangent handedness, curvature's
// scale) are derived once when the transform is set, and are what the per-hit formulas gave.
TEST(surface, the_instance_carries_the_constants_hits_read) {
  const dmat4 m = glm::rotate(glm::scale(glm::translate(dmat4(1.0), dvec3(3, -2, 1)), dvec3(2.0, -0.5, 8.0)),
                              0.7, dvec3(0.3, 1.0, -0.2));
  instance inst;
  inst.world_from_object = m;
  finish_instance_transform(inst);
  const dmat3 linear(m);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_EQ(inst.abs_linear[c][r], std::abs(linear[c][r]));
  EXPECT_TRUE(inst.mirrored);                // one negative scale
  EXPECT_NEAR(inst.mean_scale, 2.0, 1e-12);  // cbrt(|2 · -0.5 · 8|)
  inst.world_from_object = glm::scale(dmat4(1.0), dvec3(3.0));
  finish_instance_transform(inst);
  EXPECT_FALSE(inst.mirrored);
  EXPECT_NEAR(inst.mean_scale, 3.0, 1e-12);
}

// Every field of a shading point, bit for bit.
bool same_point(const surface_point& a, const surface_point& b) {
  return a.position == b.position && a.position_error == b.position_error &&
         a.geometric_normal == b.geometric_normal && a.shading_normal == b.shading_normal &&
         a.smooth_normal == b.smooth_normal && a.smooth_position == b.smooth_position &&
         a.curvature == b.curvature && a.uv0 == b.uv0 && a.uv1 == b.uv1 && a.color0 == b.color0 &&
         a.tangent == b.tangent && a.footprint0.dx == b.footprint0.dx && a.footprint0.dy == b.footprint0.dy &&
         a.footprint1.dx == b.footprint1.dx && a.footprint1.dy == b.footprint1.dy &&
         a.material == b.material && a.instance == b.instance && a.time == b.time &&
         a.front_face == b.front_face;
}

// A memo of triangle constants changes no shading point: hits on a few triangles of two meshes
// (one with vertex normals and two UV sets, one flat) under three instances (one mirrored, one
// rough and untextured), in an order that hits, misses and evicts entries, with and without a
// footprint (a triangle first met without one gets its footprint's part when it needs it).
TEST(surface, the_triangle_memo_changes_no_shading_point) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  scene s;
  mesh smooth;
  for (int k = 0; k < 12; ++k) {
    smooth.positions.push_back(vec3(unit(rng), unit(rng), unit(rng)) * 4.0f);
    smooth.normals.push_back(glm::normalize(vec3(unit(rng), unit(rng), 1.0f)));
    smooth.texcoords0.push_back(vec2(unit(rng), unit(rng)));
    smooth.texcoords1.push_back(vec2(unit(rng), unit(rng)) * 3.0f);
  }
  for (uint32_t t = 0; t < 4; ++t) smooth.indices.insert(smooth.indices.end(), {3 * t, 3 * t + 1, 3 * t + 2});
  mesh flat = smooth;
  flat.normals.clear();
  flat.texcoords1.clear();
  s.meshes = {smooth, flat};
  material textured;
  textured.roughness_factor = 0.1f;  // smooth: curvature is estimated
  textured.base_color_texture.texture = 0;
  material rough;
  rough.roughness_factor = 0.8f;
  s.materials = {textured, rough};
  const dmat4 placements[3] = {dmat4(1.0),
                               glm::scale(glm::translate(dmat4(1.0), dvec3(1, 2, 3)), dvec3(-1, 2, 0.5)),
                               glm::rotate(dmat4(1.0), 0.5, dvec3(0, 1, 0))};
  const uint32_t shapes[3] = {0, 1, 0}, materials[3] = {0, 0, 1};
  for (int i = 0; i < 3; ++i) {
    instance inst;
    inst.shape = shapes[i];
    inst.material = materials[i];
    inst.world_from_object = placements[i];
    finish_instance_transform(inst);
    s.instances.push_back(inst);
  }
  triangle_memo memo;
  int checked = 0, differing = 0;
  for (int i = 0; i < 4000; ++i) {
    hit h;
    h.instance_id = uint32_t(rng() % 3);
    h.primitive_id = uint32_t(rng() % (i < 2000 ? 2 : 4));  // few triangles first, then evictions
    h.u = 0.3f * unit(rng);
    h.v = 0.3f * unit(rng);
    const instance& inst = s.instances[h.instance_id];
    h.geometric_normal = triangle_world_normal(inst, s.meshes[inst.shape], h.primitive_id);
    ray r;
    r.origin = vec3(unit(rng), unit(rng), 10.0f) * 3.0f;
    r.direction = glm::normalize(vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, -1.0f));
    const float cone = rng() % 3 == 0 ? 0.0f : 0.01f * unit(rng);
    if (!same_point(make_surface_point(s, h, r, cone, &memo), make_surface_point(s, h, r, cone))) ++differing;
    ++checked;
  }
  EXPECT_EQ(checked, 4000);
  EXPECT_EQ(differing, 0);
  // A triangle met first without a footprint, then with one.
  triangle_memo fresh;
  hit h;
  h.instance_id = 0;
  h.u = h.v = 0.25f;
  h.geometric_normal = triangle_world_normal(s.instances[0], s.meshes[0], 0);
  ray r;
  r.origin = vec3(1.0f, 1.0f, 10.0f);
  r.direction = vec3(0, 0, -1);
  make_surface_point(s, h, r, 0.0f, &fresh);
  const surface_point with_memo = make_surface_point(s, h, r, 0.02f, &fresh);
  const surface_point without = make_surface_point(s, h, r, 0.02f);
  EXPECT_NE(without.footprint0.dx, vec2(0.0f));
  EXPECT_GT(without.curvature.major, 0.0f);
  EXPECT_TRUE(same_point(with_memo, without));
}

TEST(surface, curvature_turns_around_a_cylinder_and_not_along_it) {
  // A patch of the cylinder y² + z² = 4 along x: the normal turns at 1/2 per unit around the axis
  // (tilting along z at the top) and not at all along it, whatever steps describe the patch.
  const dvec3 n(0, 1, 0);
  const double turn = 0.1;  // radians between the patch's normals
  const dvec3 around = 2.0 * dvec3(0, std::cos(turn) - 1.0, std::sin(turn));
  const dvec3 turned = dvec3(0, std::cos(turn), std::sin(turn)) - n;
  const surface_curvature c =
      curvature_from_differentials(n, dvec3(0.3, 0, 0) + around, dvec3(0.5, 0, 0), turned, dvec3(0.0));
  EXPECT_NEAR(c.major, 0.5, 1e-3);
  EXPECT_NEAR(c.minor, 0.0, 1e-3);
  EXPECT_NEAR(std::abs(c.axis.z), 1.0, 1e-3);
  // A sphere of radius 2 turns the same every way: no axis.
  const surface_curvature sphere =
      curvature_from_differentials(n, dvec3(0.2, 0, 0), dvec3(0, 0, 0.2), dvec3(0.1, 0, 0), dvec3(0, 0, 0.1));
  EXPECT_NEAR(sphere.major, 0.5, 1e-6);
  EXPECT_NEAR(sphere.minor, 0.5, 1e-6);
  EXPECT_EQ(sphere.axis, vec3(0.0f));
  // Parallel steps describe no patch.
  EXPECT_EQ(curvature_from_differentials(n, dvec3(1, 0, 0), dvec3(2, 0, 0), dvec3(0.1), dvec3(0.2)).major,
            0.0f);
}

// A hit at barycentrics (u, v) = (0.25, 0.5) of a triangle in the z = 0 plane, and the ray along -z
// through it.
hit hit_at_a_quarter_and_a_half() {
  hit h;
  h.u = 0.25f;
  h.v = 0.5f;
  h.geometric_normal = vec3(0, 0, 1);
  return h;
}
ray ray_along_minus_z() {
  ray r;
  r.origin = {0.5f, 2.0f, 5.0f};
  r.direction = {0, 0, -1};
  return r;
}

TEST(surface, barycentric_interpolation_follows_embree_convention) {
  scene s = one_triangle(dmat4(1.0));
  const hit h = hit_at_a_quarter_and_a_half();
  const ray r = ray_along_minus_z();
  surface_point sp = make_surface_point(s, h, r);
  // p = 0.25·(1,0,0)·2 + 0.5·(0,4,0) = (0.5, 2, 0); uv = (u, v); n ∝ (0.25, 0.5, 0.25).
  EXPECT_NEAR(sp.position.x, 0.5f, 1e-6f);
  EXPECT_NEAR(sp.position.y, 2.0f, 1e-6f);
  EXPECT_NEAR(sp.uv0.x, 0.25f, 1e-6f);
  EXPECT_NEAR(sp.uv0.y, 0.5f, 1e-6f);
  vec3 expected = glm::normalize(vec3(0.25f, 0.5f, 0.25f));
  EXPECT_NEAR(sp.shading_normal.x, expected.x, 1e-6f);
  EXPECT_NEAR(sp.shading_normal.y, expected.y, 1e-6f);
  EXPECT_TRUE(sp.front_face);
}

TEST(surface, missing_normals_shade_with_the_flat_geometric_normal) {
  // glTF: without NORMAL, a primitive is flat shaded.
  scene s = one_triangle(glm::rotate(dmat4(1.0), 0.5, dvec3(1, 0, 0)));
  s.meshes[0].normals.clear();
  // The accelerator reports the world-space face normal: +z rotated 0.5 rad about x.
  const vec3 expected = glm::normalize(vec3(0, -std::sin(0.5f), std::cos(0.5f)));
  hit h;
  h.u = 0.3f;
  h.v = 0.3f;
  h.geometric_normal = expected;
  ray r;
  r.origin = {0.6f, 1.2f, 5.0f};
  r.direction = glm::normalize(vec3(0, 0.2f, -1));
  surface_point sp = make_surface_point(s, h, r);
  EXPECT_NEAR(glm::dot(sp.shading_normal, expected), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(sp.geometric_normal, expected), 1.0f, 1e-6f);
}

TEST(surface, back_face_hit_flips_both_normals_toward_the_ray) {
  scene s = one_triangle(dmat4(1.0));
  hit h;
  h.u = h.v = 0.2f;
  h.geometric_normal = vec3(0, 0, 1);
  ray r;
  r.direction = {0, 0, 1};  // arrives from below
  surface_point sp = make_surface_point(s, h, r);
  EXPECT_FALSE(sp.front_face);
  EXPECT_LT(sp.geometric_normal.z, 0.0f);
  EXPECT_LT(glm::dot(sp.shading_normal, r.direction), 0.0f);
}

TEST(surface, hit_position_error_bound_contains_the_exact_point) {
  dmat4 m = glm::translate(dmat4(1.0), dvec3(1e4, -3e3, 7e2)) * glm::scale(dmat4(1.0), dvec3(3.0, -2.0, 0.5));
  scene s = one_triangle(m);
  for (float u : {0.1f, 0.3f, 0.7f})
    for (float v : {0.05f, 0.2f}) {
      surface_position pos = triangle_hit_position(s.instances[0], s.meshes[0], 0, u, v);
      dvec3 exact = transform_point(m, dvec3(2.0 * u, 4.0 * double(v), 0.0));
      for (int a = 0; a < 3; ++a)
        EXPECT_LE(std::abs(double(pos.point[a]) - exact[a]), double(pos.error[a]) + 1e-12);
    }
}

TEST(texture_sampling, wrap_modes) {
  EXPECT_EQ(wrap_texel(-1, 4, wrap_mode::repeat), 3);
  EXPECT_EQ(wrap_texel(5, 4, wrap_mode::repeat), 1);
  EXPECT_EQ(wrap_texel(-1, 4, wrap_mode::clamp_to_edge), 0);
  EXPECT_EQ(wrap_texel(9, 4, wrap_mode::clamp_to_edge), 3);
  EXPECT_EQ(wrap_texel(4, 4, wrap_mode::mirrored_repeat), 3);
  EXPECT_EQ(wrap_texel(-1, 4, wrap_mode::mirrored_repeat), 0);
  EXPECT_EQ(wrap_texel(8, 4, wrap_mode::mirrored_repeat), 0);
}

TEST(texture_sampling, bilinear_decodes_srgb_before_filtering) {
  scene s;
  image img;
  img.width = 2;
  img.height = 1;
  img.texels8 = {0, 0, 0, 255, 255, 255, 255, 255};
  s.images.push_back(img);
  texture tex;
  tex.sampling.wrap_s = wrap_mode::clamp_to_edge;
  // Halfway between the texel centres: the mean of linear 0 and linear 1.
  vec4 c = sample_texture(s, tex, vec2(0.5f, 0.5f), texel_encoding::srgb);
  EXPECT_NEAR(c.r, 0.5f, 1e-6f);
  EXPECT_NEAR(c.a, 1.0f, 1e-6f);
  vec4 at_first = sample_texture(s, tex, vec2(0.25f, 0.5f), texel_encoding::srgb);
  EXPECT_NEAR(at_first.g, 0.0f, 1e-6f);
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.2140411f, 1e-6f);
}

TEST(material_eval, zero_specular_dielectric_is_exactly_lambert) {
  material_point mp;
  mp.base_color = vec3(0.5f, 0.25f, 1.0f);
  mp.metallic = 0.0f;
  mp.roughness = 0.5f;
  mp.specular_weight = 0.0f;
  vec3 n(0, 0, 1), v = glm::normalize(vec3(0.3f, 0.0f, 1.0f)), l = glm::normalize(vec3(-0.5f, 0.2f, 1.0f));
  vec3 f = evaluate_brdf(mp, n, v, l);
  EXPECT_NEAR(f.x, 0.5f / pi, 1e-7f);
  EXPECT_NEAR(f.z, 1.0f / pi, 1e-7f);
  EXPECT_EQ(evaluate_brdf(mp, n, v, -l), vec3(0.0f));  // light below the horizon
}

TEST(material_eval, metal_reflects_base_colour_at_normal_incidence_peak) {
  material_point mp;
  mp.base_color = vec3(0.9f, 0.6f, 0.3f);
  mp.metallic = 1.0f;
  mp.roughness = 0.3f;
  vec3 n(0, 0, 1);
  vec3 f = evaluate_brdf(mp, n, n, n);
  // At normal incidence: F = base colour, D = 1/(π α²), V = 1/4 for n = v = l.
  float alpha = 0.09f;
  float expected = 1.0f / (pi * alpha * alpha) * 0.25f;
  EXPECT_NEAR(f.x / expected, 0.9f, 1e-4f);
  EXPECT_NEAR(f.z / expected, 0.3f, 1e-4f);
}

// A point's view terms (brdf_view) are found once and serve every light direction at the point:
// each direction's lobes are those of an evaluation alone, and the sheen and the coat count in them.
TEST(material_eval, a_point_s_view_serves_all_its_light_directions) {
  material_point mp;
  mp.base_color = vec3(0.6f, 0.3f, 0.2f);
  mp.roughness = 0.4f;
  material_layers& layers = mp.layers.emplace();
  layers.sheen_color = vec3(0.8f, 0.7f, 0.9f);
  layers.sheen_roughness = 0.3f;
  layers.clearcoat = 1.0f;
  layers.clearcoat_roughness = 0.2f;
  layers.clearcoat_normal = glm::normalize(vec3(0.1f, 0.0f, 1.0f));
  const vec3 n(0, 0, 1), v = glm::normalize(vec3(0.3f, -0.2f, 1.0f));
  const brdf_view view = brdf_view_of(mp, n, v);
  EXPECT_GT(view.sheen_lambda_v, 0.0f);
  EXPECT_GT(view.coat_weight, 0.0f);
  material_point bare = mp;
  bare.layers.reset();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int layered = 0;
  for (int i = 0; i < 300; ++i) {
    const vec3 l = glm::normalize(vec3(u(rng), u(rng), u(rng) + 0.3f));
    const brdf_lobes shared = evaluate_brdf_lobes(view, mp, n, v, l, highlight_footprint{});
    const brdf_lobes alone = evaluate_brdf_lobes(mp, n, v, l);
    EXPECT_EQ(shared.diffuse, alone.diffuse);
    EXPECT_EQ(shared.specular, alone.specular);
    EXPECT_EQ(evaluate_brdf(view, mp, n, v, l, highlight_footprint{}), evaluate_brdf(mp, n, v, l));
    if (alone.specular != evaluate_brdf_lobes(bare, n, v, l).specular) ++layered;
    const float n_dot_l = glm::dot(n, l);
    if (n_dot_l > 0.0f)
      EXPECT_EQ(charlie_visibility_from(0.3f, charlie_lambda_at(0.3f, view.n_dot_v), view.n_dot_v, n_dot_l),
                charlie_visibility(0.3f, view.n_dot_v, n_dot_l));
  }
  EXPECT_GT(layered, 200);
}

TEST(lights, point_light_follows_inverse_square) {
  light l;
  l.position = dvec3(0, 0, 2);
  l.intensity = 8.0f;
  light_sample a = sample_light(l, vec3(0));
  EXPECT_NEAR(a.irradiance.x, 2.0f, 1e-6f);
  EXPECT_NEAR(a.distance, 2.0f, 1e-6f);
  EXPECT_NEAR(a.direction.z, 1.0f, 1e-6f);
  l.range = 1.0f;  // beyond range: nothing
  EXPECT_EQ(sample_light(l, vec3(0)).irradiance, vec3(0.0f));
}

TEST(lights, range_window_is_the_specifications_recommendation) {
  light l;
  l.position = dvec3(0, 0, 2);
  l.intensity = 8.0f;
  l.range = 4.0f;  // d/range = 1/2: window 1 - 1/16, on top of 8/2²
  EXPECT_NEAR(sample_light(l, vec3(0)).irradiance.x, 2.0f * (1.0f - 1.0f / 16.0f), 1e-6f);
  l.range = 2.0f;  // exactly at the range: nothing
  EXPECT_EQ(sample_light(l, vec3(0)).irradiance, vec3(0.0f));
}

TEST(lights, spot_cone_is_full_inside_inner_and_zero_outside_outer) {
  light l;
  l.kind = light_kind::spot;
  l.position = dvec3(0, 0, 1);
  l.direction = vec3(0, 0, -1);
  l.inner_cone_angle = 0.2f;
  l.outer_cone_angle = 0.4f;
  EXPECT_NEAR(sample_light(l, vec3(0, 0, 0)).irradiance.x, 1.0f, 1e-6f);
  EXPECT_EQ(sample_light(l, vec3(std::tan(0.5f), 0, 0)).irradiance, vec3(0.0f));
  // Between the cones glTF interpolates linearly in cos(angle), then squares. The point at
  // tan(0.3) lies at 0.3 rad off the axis, at distance 1/cos(0.3).
  const float cos_angle = std::cos(0.3f), cos_inner = std::cos(0.2f), cos_outer = std::cos(0.4f);
  const float t = (cos_angle - cos_outer) / (cos_inner - cos_outer);
  const float expected = t * t * cos_angle * cos_angle;  // times the inverse square of 1/cos(0.3)
  EXPECT_NEAR(sample_light(l, vec3(std::tan(0.3f), 0, 0)).irradiance.x, expected, 1e-5f);
}

TEST(lights, directional_light_is_constant_irradiance) {
  light l;
  l.kind = light_kind::directional;
  l.direction = vec3(0, -1, 0);
  l.intensity = 3.0f;
  light_sample ls = sample_light(l, vec3(100, 5, -7));
  EXPECT_NEAR(ls.irradiance.y, 3.0f, 1e-6f);
  EXPECT_EQ(ls.direction, vec3(0, 1, 0));
  EXPECT_TRUE(std::isinf(ls.distance));
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

TEST(texture_sampling, texture_transform_scales_rotates_then_offsets) {
  texture_ref ref;
  EXPECT_EQ(transform_uv(ref, vec2(0.3f, 0.7f)), vec2(0.3f, 0.7f));  // identity by default
  ref.uv_scale = vec2(2.0f, 3.0f);
  ref.offset = vec2(0.5f, -1.0f);
  vec2 a = transform_uv(ref, vec2(0.25f, 0.5f));
  EXPECT_NEAR(a.x, 1.0f, 1e-6f);
  EXPECT_NEAR(a.y, 0.5f, 1e-6f);
  // A quarter turn counter-clockwise on the image (v points down): +u goes to -v.
  ref.rotation = pi / 2;
  vec2 b = transform_uv(ref, vec2(0.5f, 0.0f));  // scaled to (1, 0), rotated to (0, -1)
  EXPECT_NEAR(b.x, 0.5f, 1e-6f);
  EXPECT_NEAR(b.y, -2.0f, 1e-6f);
}

TEST(material_eval, vertex_colour_and_second_uv_set) {
  scene s;
  image img;
  img.width = 2;
  img.height = 1;
  img.texels8 = {255, 255, 255, 255, 0, 0, 0, 255};  // white | black
  s.images.push_back(img);
  texture tex;
  tex.sampling = {wrap_mode::clamp_to_edge, wrap_mode::clamp_to_edge, filter_mode::nearest};
  s.textures.push_back(tex);
  material m;
  m.base_color_texture.texture = 0;
  m.base_color_texture.texcoord = 1;
  material_inputs in;
  in.uv[0] = vec2(0.9f, 0.5f);  // black texel: must not be read
  in.uv[1] = vec2(0.1f, 0.5f);  // white texel
  in.color0 = vec4(0.5f, 0.25f, 1.0f, 0.5f);
  material_point mp = evaluate_material(s, m, in);
  EXPECT_EQ(mp.base_color, vec3(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(mp.alpha, 0.5f);
}

}  // namespace
}  // namespace kiln

#include "shade/normal_mapping.h"

namespace kiln {
namespace {

TEST(normal_mapping, tilts_the_shading_normal_in_the_tangent_frame) {
  scene s;
  image img;
  img.width = img.height = 1;
  img.texels8 = {255, 128, 128, 255};  // tangent-space normal ≈ (1, 0, 0): along the tangent
  s.images.push_back(img);
  s.textures.emplace_back();
  material m;
  m.normal_texture.texture = 0;
  m.normal_texture.scale = 1.0f;
  surface_point sp;
  sp.geometric_normal = sp.shading_normal = vec3(0, 0, 1);
  sp.tangent = vec4(0, 1, 0, 1);  // tangent +y
  apply_normal_map(s, m, material_inputs{}, sp);
  // c = (1, 0.0039, 0.0039): almost exactly the tangent, nudged toward +z so it stays above.
  EXPECT_GT(sp.shading_normal.y, 0.99f);
  EXPECT_GT(sp.shading_normal.z, 0.0f);
  // Scale 0 flattens X and Y: the map then returns the interpolated normal.
  m.normal_texture.scale = 0.0f;
  sp.shading_normal = vec3(0, 0, 1);
  apply_normal_map(s, m, material_inputs{}, sp);
  EXPECT_NEAR(sp.shading_normal.z, 1.0f, 1e-6f);
  // A back-face hit maps in glTF's frame and flips the result toward the ray.
  m.normal_texture.scale = 0.5f;
  surface_point back;
  back.front_face = false;
  back.geometric_normal = back.shading_normal = vec3(0, 0, -1);
  back.tangent = vec4(0, 1, 0, 1);
  apply_normal_map(s, m, material_inputs{}, back);
  EXPECT_LT(back.shading_normal.z, 0.0f);
  EXPECT_LT(back.shading_normal.y, 0.0f);
}

}  // namespace
}  // namespace kiln

#include "shade/environment.h"

namespace kiln {
namespace {

TEST(environment, equirectangular_directions_and_rotation) {
  vec2 front = environment_uv(vec3(0, 0, -1), 0.0f);
  EXPECT_NEAR(front.x, 0.5f, 1e-6f);
  EXPECT_NEAR(front.y, 0.5f, 1e-6f);
  EXPECT_NEAR(environment_uv(vec3(2, 0, 0), 0.0f).x, 0.75f, 1e-6f);
  EXPECT_NEAR(environment_uv(vec3(0, 1, 0), 0.0f).y, 0.0f, 1e-6f);
  EXPECT_NEAR(environment_uv(vec3(0, -1, 0), 0.0f).y, 1.0f, 1e-6f);
  // A quarter turn counter-clockwise (seen from above) brings the map centre from -Z to +X.
  EXPECT_NEAR(environment_uv(vec3(1, 0, 0), pi / 2).x, 0.5f, 1e-6f);
}

TEST(environment, map_radiance_is_scaled_by_intensity_and_constant_colour_otherwise) {
  scene s;
  s.env.color = vec3(0.25f);
  EXPECT_EQ(environment_radiance(s, vec3(0, 0, -1)), vec3(0.25f));
  image sky;  // 4x2: top row bright, bottom row dark
  sky.width = 4;
  sky.height = 2;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      sky.texels32.insert(sky.texels32.end(), {y ? 0.5f : 8.0f, float(x), 0.0f, 1.0f});
  s.images.push_back(sky);
  s.env.map_image = 0;
  s.env.intensity = 2.0f;
  EXPECT_NEAR(environment_radiance(s, vec3(0, 1, 0)).x, 16.0f, 1e-5f);  // straight up: top row
  EXPECT_NEAR(environment_radiance(s, vec3(0, -1, 0)).x, 1.0f, 1e-5f);  // straight down: bottom row
  // Slightly above the horizon along +X: u = 0.75 is the centre of texel column 2.5 -> between 2 and 3.
  EXPECT_NEAR(environment_radiance(s, vec3(1, 0.05f, 0)).y, 2.0f * 2.5f, 1e-3f);
}

// A triangle's footprint: a cone of width w arriving at 60° from the normal covers w/cos 60° along
// the projected ray and w across it; the triangle maps 2 world units to one u and 4 to one v.
TEST(texture_footprint, triangle_footprint_is_the_cone_section_through_the_uv_jacobian) {
  scene s = one_triangle(dmat4(1.0));
  s.materials[0].base_color_texture.texture = 0;  // the footprint only feeds texture lookups
  hit h;
  h.u = h.v = 0.25f;
  h.geometric_normal = vec3(0, 0, 1);
  ray r;
  const float angle = glm::radians(60.0f);
  r.direction = vec3(std::sin(angle), 0.0f, -std::cos(angle));  // projected direction: +x (u)
  const float w = 0.01f;
  const surface_point sp = make_surface_point(s, h, r, w);
  EXPECT_NEAR(sp.footprint0.dx.x, w / std::cos(angle) / 2.0f, 1e-6f);
  EXPECT_NEAR(sp.footprint0.dx.y, 0.0f, 1e-7f);
  EXPECT_NEAR(sp.footprint0.dy.x, 0.0f, 1e-7f);
  EXPECT_NEAR(std::abs(sp.footprint0.dy.y), w / 4.0f, 1e-6f);
  EXPECT_TRUE(make_surface_point(s, h, r).footprint0.empty());  // no cone, no footprint
  s.materials[0].base_color_texture.texture = -1;
  EXPECT_TRUE(make_surface_point(s, h, r, w).footprint0.empty());  // nothing reads it
}

// A sphere of radius 2 seen head-on at its equator on the u seam: u = φ/2π and v = θ/π, so one unit
// of u spans 2π·2 and one of v spans π·2; the numerical Jacobian must fold the seam.
TEST(texture_footprint, sphere_footprint_follows_its_parametric_uv) {
  scene s;
  quadric q;
  q.kind = quadric_kind::sphere;
  q.radius = 2.0;
  q.bounds = quadric_bounds(q);
  s.quadrics.push_back(q);
  s.materials.emplace_back();
  s.materials[0].base_color_texture.texture = 0;  // the footprint only feeds texture lookups
  instance inst;
  inst.kind = shape_kind::quadric;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
  ray r;
  r.origin = vec3(5, 0, 0);
  r.direction = vec3(-1, 0, 0);
  hit h;
  h.t = 3.0f;
  h.geometric_normal = vec3(1, 0, 0);
  const float w = 0.02f;
  const surface_point sp = make_surface_point(s, h, r, w);
  const float du = w / (2.0f * pi * 2.0f), dv = w / (pi * 2.0f);
  // Normal incidence: the footprint is a circle; its axes start along dp/du.
  EXPECT_NEAR(std::abs(sp.footprint0.dx.x), du, 1e-3f * du);
  EXPECT_NEAR(sp.footprint0.dx.y, 0.0f, 1e-3f * dv);
  EXPECT_NEAR(sp.footprint0.dy.x, 0.0f, 1e-3f * du);
  EXPECT_NEAR(std::abs(sp.footprint0.dy.y), dv, 1e-3f * dv);
}

// A quadric's curvature has its two principal directions: a cylinder of radius 0.5 along x turns
// its normal at 2 per unit around the axis (tilting along z at the top) and not along it; a sphere
// of radius 2 turns at 1/2 every way. (The largest turn taken every way stretched a cylinder's
// highlight off its ends.)
TEST(surface, a_quadric_s_curvature_has_its_two_principal_directions) {
  auto curvature_at_top = [](quadric_kind kind, double radius, const dmat4& world_from_object) {
    scene s;
    quadric q;
    q.kind = kind;
    q.radius = radius;
    q.zmin = -1.0;
    q.zmax = 1.0;
    q.bounds = quadric_bounds(q);
    s.quadrics.push_back(q);
    s.materials.emplace_back();
    s.materials[0].roughness_factor = 0.1f;  // smooth enough to need the curvature
    instance inst;
    inst.kind = shape_kind::quadric;
    inst.world_from_object = world_from_object;
    finish_instance_transform(inst);
    s.instances.push_back(inst);
    ray r;
    r.origin = vec3(0, 5, 0);
    r.direction = vec3(0, -1, 0);
    hit h;
    h.t = float(5.0 - radius);
    h.primitive_id = quadric_side;
    h.geometric_normal = vec3(0, 1, 0);
    return make_surface_point(s, h, r, 0.01f).curvature;
  };
  const surface_curvature cylinder = curvature_at_top(
      quadric_kind::cylinder, 0.5, glm::rotate(dmat4(1.0), 0.5 * double(pi), dvec3(0, 1, 0)));
  EXPECT_NEAR(cylinder.major, 2.0f, 1e-5f);
  EXPECT_NEAR(cylinder.minor, 0.0f, 1e-5f);
  EXPECT_NEAR(std::abs(cylinder.axis.z), 1.0f, 1e-5f);
  const surface_curvature sphere = curvature_at_top(quadric_kind::sphere, 2.0, dmat4(1.0));
  EXPECT_NEAR(sphere.major, 0.5f, 1e-5f);
  EXPECT_NEAR(sphere.minor, 0.5f, 1e-5f);
  EXPECT_EQ(sphere.axis, vec3(0.0f));
}

// Refraction scales the spread as Snell's law bends two nearby rays: refract two directions dθ apart
// through a plane and measure the angle between the refracted pair.
TEST(ray_cone, refracted_spread_matches_snell_on_two_nearby_rays) {
  const vec3 n(0, 0, 1);
  const float eta = 1.0f / 1.5f, d_theta = 1e-2f;
  auto incoming = [](float a) { return vec3(std::sin(a), 0.0f, -std::cos(a)); };
  for (float degrees : {0.0f, 20.0f, 45.0f, 70.0f}) {
    const float a = glm::radians(degrees);
    // Two rays d_theta apart, centred on a; the angle between the refracted pair from atan2 (acos
    // loses small angles in float).
    const vec3 t0 = *refract_direction(incoming(a - 0.5f * d_theta), n, eta);
    const vec3 t1 = *refract_direction(incoming(a + 0.5f * d_theta), n, eta);
    const float bent = std::atan2(glm::length(glm::cross(t0, t1)), glm::dot(t0, t1));
    const vec3 centre = *refract_direction(incoming(a), n, eta);
    const ray_cone out = refracted_cone({0.5f, d_theta}, eta, glm::dot(incoming(a), n), glm::dot(centre, n));
    EXPECT_NEAR(out.spread, bent, 1e-2f * bent) << degrees;
    EXPECT_EQ(out.width, 0.5f);
  }
}

// A planar mirror keeps the cone: after travelling d1 to the mirror and d2 beyond it, the width is
// that of one straight ray of length d1 + d2.
TEST(ray_cone, width_after_planar_mirror_equals_unfolded_straight_width) {
  const ray_cone camera{0.0f, 2e-3f};
  const ray_cone folded = cone_at(reflected_cone(cone_at(camera, 3.0f)), 7.5f);
  EXPECT_FLOAT_EQ(folded.width, cone_at(camera, 10.5f).width);
  EXPECT_FLOAT_EQ(folded.spread, camera.spread);
}

}  // namespace
}  // namespace kiln
