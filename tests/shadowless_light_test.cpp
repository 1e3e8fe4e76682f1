// A light with casts_shadows off (kiln's default headlight) lights a point whatever lies between
// them; a glTF light is blocked. Through the real shading code and the Embree backend.
#include <gtest/gtest.h>

#include "accel/embree/embree_accelerator.h"
#include "shade/whitted.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

using testing::add_quad;
using testing::make_ray;

TEST(shadowless_light, lights_through_an_occluder_that_blocks_a_shadow_casting_light) {
  scene s;
  material diffuse;
  diffuse.metallic_factor = 0.0f;
  diffuse.specular_factor = 0.0f;
  diffuse.base_color_factor = vec4(0.5f, 0.5f, 0.5f, 1.0f);
  diffuse.double_sided = true;
  s.materials = {diffuse};
  add_quad(s, -5, -5, 5, 5, 0.0f, 0);  // the floor
  add_quad(s, -1, -1, 1, 1, 1.0f, 0);  // an occluder right above the shaded point
  light l;
  l.position = dvec3(0.0, 0.0, 2.0);
  l.intensity = 4.0f;
  s.lights = {l};
  embree_accelerator accel(s);
  shading_options options;
  // The camera looks at the floor point (0.1, 0.1, 0) from below the occluder.
  const ray camera = make_ray(vec3(0.1f, 0.1f, 0.5f), vec3(0, 0, -1));
  for (bool casts : {true, false}) {
    s.lights[0].casts_shadows = casts;
    shading_context ctx{s, accel, options, scene_has_see_through(s)};
    ray_counts counts;
    const vec3 radiance = trace_radiance(ctx, camera, path_state{}, counts);
    if (casts) {
      EXPECT_EQ(radiance, vec3(0.0f));
      EXPECT_EQ(counts.shadow, 1u);
    } else {
      // Lambert: (albedo / π) · I · cosθ / r², the point 2 below the light and slightly off axis.
      const double r2 = 0.1 * 0.1 * 2 + 4.0, cos_theta = 2.0 / std::sqrt(r2);
      EXPECT_NEAR(radiance.x, 0.5 / pi * 4.0 * cos_theta / r2, 1e-4);
      EXPECT_EQ(counts.shadow, 0u);
    }
  }
}

}  // namespace
}  // namespace kiln
