// Analytic refraction checks through the real shading code and the Embree
// backend: a glass slab shifts a ray by the exact Snell offset, head-on
// reflectance of a slab sums the Fresnel series, total internal reflection
// sends nothing through, Beer-Lambert absorption over a known length, and
// shadows through a transmissive sheet take its transmission colour.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "shade/dielectric.h"
#include "shade/whitted.h"
#include "support/shadow_probe.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

using testing::add_box;
using testing::emitter;
using testing::make_ray;

// Passes queries on to a real backend and records every ray handed to
// intersect().
class recording_accelerator final : public accelerator {
 public:
  explicit recording_accelerator(const accelerator& inner) : inner_(inner) {}
  std::optional<hit> intersect(const ray& r) const override {
    rays.push_back(r);
    return inner_.intersect(r);
  }
  bool occluded(const ray& r) const override { return inner_.occluded(r); }
  mutable std::vector<ray> rays;

 private:
  const accelerator& inner_;
};

// Smooth glass: all of the dielectric part transmits; no diffuse, no faded
// mirror.
material glass(float ior, bool volume) {
  material m;
  m.metallic_factor = 0.0f;
  m.roughness_factor = 0.0f;
  m.transmission_factor = 1.0f;
  m.ior = ior;
  m.thickness_factor = volume ? 1.0f : 0.0f;
  return m;
}

TEST(dielectric, normal_incidence_fresnel_is_the_squared_ratio) {
  for (auto [n1, n2] : {std::pair{1.0f, 1.5f}, {1.5f, 1.0f}, {1.33f, 1.5f}, {1.0f, 2.4f}}) {
    float expected = (n1 - n2) / (n1 + n2);
    EXPECT_NEAR(fresnel_dielectric(1.0f, n1 / n2), expected * expected, 1e-7f) << n1 << " -> " << n2;
  }
  EXPECT_EQ(fresnel_dielectric(0.3f, 1.0f),
            0.0f);  // index-matched: no interface
}

TEST(dielectric, total_internal_reflection_beyond_the_critical_angle) {
  const float eta = 1.5f;  // glass to vacuum
  const float critical = std::asin(1.0f / eta);
  for (float angle : {critical + 0.01f, 1.0f, 1.5f}) {
    vec3 d(std::sin(angle), 0.0f, -std::cos(angle));
    EXPECT_FALSE(refract_direction(d, vec3(0, 0, 1), eta).has_value());
    EXPECT_EQ(fresnel_dielectric(std::cos(angle), eta), 1.0f);
  }
  float below = critical - 0.01f;
  std::optional<vec3> t =
      refract_direction(vec3(std::sin(below), 0.0f, -std::cos(below)), vec3(0, 0, 1), eta);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(t->x, eta * std::sin(below),
              1e-5f);  // Snell: n1 sin θi = n2 sin θt
  EXPECT_LT(fresnel_dielectric(std::cos(below), eta), 1.0f);
}

TEST(dielectric, medium_stack_resolves_nested_and_touching_media) {
  scene s;
  s.materials = {glass(1.5f, true), glass(1.33f, true)};
  medium_stack air;
  EXPECT_EQ(air.ior(s), 1.0f);
  medium_stack in_water = air.with(1);
  medium_stack in_glass_in_water = in_water.with(0);
  EXPECT_EQ(in_glass_in_water.ior(s), 1.5f);
  EXPECT_EQ(in_glass_in_water.without(0).ior(s), 1.33f);
  // Leaving the water first while still inside the glass (touching volumes):
  // glass remains.
  EXPECT_EQ(in_glass_in_water.without(1).ior(s), 1.5f);
  EXPECT_EQ(in_glass_in_water.without(1).without(0).ior(s), 1.0f);
}

TEST(refraction, glass_slab_shifts_a_ray_by_the_snell_offset) {
  const float thickness = 0.5f, n = 1.5f;
  scene s;
  s.materials = {glass(n, true)};
  add_box(s, vec3(-100, -100, -thickness), vec3(100, 100, 0), 0);
  embree_accelerator embree(s);
  recording_accelerator accel(embree);
  shading_options options;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  for (float angle : {0.2f, 0.6f, 1.0f}) {
    accel.rays.clear();
    ray_counts counts;
    ray camera = make_ray(vec3(0, 0, 1), vec3(std::sin(angle), 0.0f, -std::cos(angle)));
    trace_radiance(ctx, camera, path_state{}, counts);
    // The first ray that left the bottom face going down (later ones follow
    // internal reflections).
    const ray* exit = nullptr;
    for (const ray& r : accel.rays)
      if (!exit && std::abs(r.origin.z + thickness) < 1e-4f && r.direction.z < 0.0f) exit = &r;
    ASSERT_NE(exit, nullptr) << angle;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(exit->direction[a], camera.direction[a], 2e-6f) << angle;
    float angle_t = std::asin(std::sin(angle) / n);
    float expected_x = std::tan(angle) + thickness * std::tan(angle_t);
    EXPECT_NEAR(exit->origin.x, expected_x, 2e-5f) << angle;
    // Perpendicular distance between the incident line and the exit line:
    // t·sin(θi−θt)/cos θt.
    vec3 between = exit->origin - camera.origin;
    float offset = glm::length(between - glm::dot(between, camera.direction) * camera.direction);
    EXPECT_NEAR(offset, thickness * std::sin(angle - angle_t) / std::cos(angle_t), 2e-5f) << angle;
    EXPECT_GE(counts.refraction, 2u);
  }
}

TEST(refraction, head_on_slab_reflects_the_fresnel_series) {
  // Emitter behind the camera, black elsewhere: the camera sees F + (1-F)²F(1 +
  // F² + ...) = 2F/(1+F), the reflectance of a non-absorbing slab with F =
  // ((n-1)/(n+1))².
  const float n = 1.5f, radiance = 10.0f;
  scene s;
  s.materials = {glass(n, true), emitter(radiance)};
  add_box(s, vec3(-50, -50, -1), vec3(50, 50, 0), 0);
  add_box(s, vec3(-50, -50, 3), vec3(50, 50, 3.5f), 1);
  embree_accelerator accel(s);
  shading_options options;
  options.min_throughput = 0.0f;  // the third term of the series weighs only F³
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  vec3 seen = trace_radiance(ctx, make_ray(vec3(0, 0, 1), vec3(0, 0, -1)), path_state{}, counts);
  float f = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
  EXPECT_NEAR(seen.x / radiance, 2.0f * f / (1.0f + f), 1e-5f);
  EXPECT_EQ(seen.x, seen.z);
}

TEST(refraction, total_internal_reflection_traces_no_refracted_ray) {
  // A ray starting inside a glass block meets its top face: beyond the critical
  // angle nothing leaves, below it one refracted ray does.
  scene s;
  s.materials = {glass(1.5f, true)};
  add_box(s, vec3(-100, -100, -1), vec3(100, 100, 0), 0);
  embree_accelerator accel(s);
  shading_options options;
  options.max_depth = 1;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  const float critical = std::asin(1.0f / 1.5f);
  path_state inside;
  inside.media = medium_stack{}.with(0);
  for (auto [angle, refracted] : {std::pair{critical + 0.02f, 0u}, {critical - 0.02f, 1u}}) {
    ray_counts counts;
    trace_radiance(ctx, make_ray(vec3(0, 0, -0.5f), vec3(std::sin(angle), 0.0f, std::cos(angle))), inside,
                   counts);
    EXPECT_EQ(counts.refraction, refracted) << angle;
    EXPECT_EQ(counts.reflection, 1u) << angle;
  }
}

TEST(refraction, beer_lambert_attenuation_over_a_known_length) {
  // ior 1: no Fresnel reflection, no bending; the white environment seen
  // through a block of length L is attenuation_color^(L /
  // attenuation_distance).
  const float length = 2.0f, distance = 0.8f;
  const vec3 colour(0.9f, 0.5f, 0.2f);
  scene s;
  material m = glass(1.0f, true);
  m.attenuation_color = colour;
  m.attenuation_distance = distance;
  s.materials = {m};
  s.env.color = vec3(1.0f);
  add_box(s, vec3(-1, -1, -length), vec3(1, 1, 0), 0);
  embree_accelerator accel(s);
  shading_options options;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  vec3 seen = trace_radiance(ctx, make_ray(vec3(0.1f, 0.2f, 3), vec3(0, 0, -1)), path_state{}, counts);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], std::pow(colour[c], length / distance), 1e-5f) << c;
  EXPECT_NEAR(beer_transmittance(colour, distance, 0.0f).x, 1.0f, 0.0f);
}

TEST(refraction, shadow_through_a_transmissive_sheet_takes_its_colour) {
  // Diffuse floor under a point light; a thin-walled sheet of tinted glass
  // covers half of it.
  scene s;
  material floor;
  floor.metallic_factor = 0.0f;
  floor.specular_factor = 0.0f;
  material sheet = glass(1.5f, false);
  const vec3 tint(0.5f, 0.25f, 1.0f);
  sheet.base_color_factor = vec4(tint, 1.0f);
  s.materials = {floor, sheet};
  add_box(s, vec3(0, -10, 1), vec3(10, 10, 1.01f), 1);  // two crossings
  vec3 through = testing::light_through_cover(s);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(through[c], tint[c] * tint[c], 1e-5f) << c;
}

}  // namespace
}  // namespace kiln
