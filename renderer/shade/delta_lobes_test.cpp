#include "shade/delta_lobes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiln {
namespace {

constexpr float mirror_limit = 0.25f;

// A surface at the origin facing +Z, hit from above (front face) unless from_below.
surface_point flat_point(bool from_below = false) {
  surface_point sp;
  const vec3 n(0.0f, 0.0f, from_below ? -1.0f : 1.0f);
  sp.geometric_normal = sp.shading_normal = sp.smooth_normal = n;
  sp.front_face = !from_below;
  sp.material = 0;
  return sp;
}

// Smooth glass: the dielectric transmits all it does not reflect.
material_point glass_point() {
  material_point mp;
  mp.base_color = vec3(1.0f);
  mp.metallic = 0.0f;
  mp.roughness = 0.0f;
  mp.transmission = 1.0f;
  return mp;
}

scene glass_scene(float dispersion = 0.0f) {
  scene s;
  material m;
  m.transmission_factor = 1.0f;
  m.metallic_factor = 0.0f;
  m.roughness_factor = 0.0f;
  m.thickness_factor = 1.0f;  // a volume
  m.dispersion = dispersion;
  s.materials.push_back(m);
  return s;
}

float schlick_free_fresnel(float n1, float n2) { return std::pow((n1 - n2) / (n1 + n2), 2.0f); }

// At normal incidence into glass, exact Fresnel reflects ((1 - 1.5) / (1 + 1.5))² = 4% by the mirror
// and refracts the rest straight on, into the glass's volume: the lobes share all the light.
TEST(delta_lobes, smooth_glass_splits_light_between_refraction_and_mirror) {
  const scene s = glass_scene();
  const delta_lobes d =
      delta_lobes_at(s, mirror_limit, flat_point(), glass_point(), vec3(0, 0, -1), medium_stack{}, -1);
  ASSERT_EQ(d.count, 2);
  const delta_lobe& refraction = d.lobes[0];
  const delta_lobe& mirror = d.lobes[1];
  EXPECT_EQ(refraction.kind, delta_kind::refraction);
  EXPECT_EQ(mirror.kind, delta_kind::mirror);
  const float f = schlick_free_fresnel(1.0f, 1.5f);
  EXPECT_NEAR(mirror.weight.x, f, 1e-6f);
  EXPECT_NEAR(refraction.weight.x, 1.0f - f, 1e-6f);
  EXPECT_NEAR(refraction.direction.z, -1.0f, 1e-6f);
  EXPECT_NEAR(mirror.direction.z, 1.0f, 1e-6f);
  EXPECT_TRUE(refraction.media.contains(0));
  EXPECT_TRUE(mirror.media.empty());
  EXPECT_NEAR(refraction.eta, 1.0f / 1.5f, 1e-6f);
}

// Leaving glass past the critical angle (sin θ > 1/1.5) nothing refracts: the mirror takes it all.
TEST(delta_lobes, total_internal_reflection_leaves_only_the_mirror) {
  const scene s = glass_scene();
  const medium_stack inside = medium_stack{}.with(0);
  const float angle = 60.0f * pi / 180.0f;
  const vec3 incident(std::sin(angle), 0.0f, std::cos(angle));  // upward, hitting the top from below
  const delta_lobes d =
      delta_lobes_at(s, mirror_limit, flat_point(true), glass_point(), incident, inside, -1);
  ASSERT_EQ(d.count, 1);
  EXPECT_EQ(d.lobes[0].kind, delta_kind::mirror);
  EXPECT_NEAR(d.lobes[0].weight.x, 1.0f, 1e-6f);
  EXPECT_LT(d.lobes[0].direction.z, 0.0f);  // back down into the glass
  EXPECT_TRUE(d.lobes[0].media.contains(0));
}

// A dispersive volume entered by a ray of all colours: one refraction per channel, each carrying its
// channel alone and bent by its own ior (blue, the highest, bends most).
TEST(delta_lobes, dispersion_splits_refraction_by_channel) {
  const scene s = glass_scene(1.0f);
  const vec3 incident = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  const delta_lobes d =
      delta_lobes_at(s, mirror_limit, flat_point(), glass_point(), incident, medium_stack{}, -1);
  ASSERT_EQ(d.count, 4);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(d.lobes[c].kind, delta_kind::refraction);
    EXPECT_EQ(d.lobes[c].channel, c);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(d.lobes[c].weight[k] > 0.0f, k == c) << c << " " << k;
  }
  EXPECT_GT(d.lobes[0].direction.x, d.lobes[2].direction.x);  // red keeps more of its slant
  // A ray already of one channel refracts once more, by its own channel's ior.
  const delta_lobes red =
      delta_lobes_at(s, mirror_limit, flat_point(), glass_point(), incident, medium_stack{}, 0);
  ASSERT_EQ(red.count, 2);
  EXPECT_EQ(red.lobes[0].channel, 0);
  EXPECT_EQ(red.lobes[0].direction, d.lobes[0].direction);
}

// The mirror fades out linearly with roughness and is gone at the limit; a clearcoat about its own
// normal gets its own mirror with the coat's Fresnel weight (F0 0.04 at normal incidence).
TEST(delta_lobes, mirror_fades_with_roughness_and_the_coat_has_its_own) {
  scene s;
  s.materials.push_back(material{});
  material_point metal;
  metal.base_color = vec3(0.8f);
  metal.metallic = 1.0f;
  metal.roughness = 0.125f;
  const vec3 down(0, 0, -1);
  delta_lobes d = delta_lobes_at(s, mirror_limit, flat_point(), metal, down, medium_stack{}, -1);
  ASSERT_EQ(d.count, 1);
  EXPECT_NEAR(d.lobes[0].weight.x, 0.8f * 0.5f, 1e-6f);
  metal.roughness = mirror_limit;
  d = delta_lobes_at(s, mirror_limit, flat_point(), metal, down, medium_stack{}, -1);
  EXPECT_EQ(d.lobes[0].weight, vec3(0.0f));

  material_layers coat;
  coat.clearcoat = 1.0f;
  coat.clearcoat_normal = glm::normalize(vec3(0.1f, 0.0f, 1.0f));
  metal.layers = coat;
  d = delta_lobes_at(s, mirror_limit, flat_point(), metal, down, medium_stack{}, -1);
  ASSERT_EQ(d.count, 2);
  EXPECT_EQ(d.lobes[1].kind, delta_kind::coat_mirror);
  const float cos_coat = coat.clearcoat_normal.z;
  EXPECT_NEAR(d.lobes[1].weight.x, fresnel_schlick(vec3(0.04f), cos_coat).x, 1e-6f);
  EXPECT_NEAR(glm::dot(d.lobes[1].direction, coat.clearcoat_normal), cos_coat, 1e-5f);
}

}  // namespace
}  // namespace kiln
