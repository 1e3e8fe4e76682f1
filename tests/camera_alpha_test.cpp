// Alpha is coverage × opacity along the camera's path: BLEND layers over nothing leave 1 − Π(1 − αi),
// with premultiplied colour and no background baked in; glass holds out by default and, with
// transmission transparent, passes what it refracts into the background as transparency. Cryptomatte
// coverage of the layers sums to alpha. Closed forms on quads facing the camera, rendered through the
// real tile renderer and the Embree backend.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/embree/embree_accelerator.h"
#include "render/tile_renderer.h"
#include "shade/dielectric.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

using testing::add_quad;

constexpr int size = 16;

// Only emits: colour c · alpha reaches the camera from a BLEND layer, nothing else.
material blend_emitter(float radiance, float alpha) {
  material m = testing::emitter(radiance);
  m.base_color_factor.a = alpha;
  m.alpha = alpha_mode::blend;
  m.double_sided = true;
  return m;
}

// Thin-walled clear glass: no diffuse, exact Fresnel split, rays pass on unbent.
material thin_glass() {
  material m;
  m.metallic_factor = 0.0f;
  m.roughness_factor = 0.0f;
  m.transmission_factor = 1.0f;
  m.double_sided = true;
  return m;
}

struct rendered {
  film image;
  double alpha(int x, int y) const { return image.color[image.index(x, y)].a; }
};

// Quads covering the whole view at z = 0, -1, ... (material i on quad i), looked at head-on.
rendered render_layers(const std::vector<material>& layers, bool transparent_glass = false,
                       vec3 background = vec3(0.0f), bool show_background = false) {
  scene s;
  s.materials = layers;
  for (size_t i = 0; i < layers.size(); ++i) add_quad(s, -10, -10, 10, 10, -float(i), uint32_t(i));
  s.env.color = background;
  embree_accelerator accel(s);
  render_settings settings;
  settings.threads = 1;
  settings.samples_per_pixel = 4;
  settings.show_background = show_background;
  settings.shading.transmission_transparent = transparent_glass;
  settings.aovs.set(aov::crypto_object);
  settings.aovs.crypto_depth = 4;
  for (uint32_t i = 0; i < layers.size(); ++i) settings.mattes.object_by_node.push_back(100 + i);
  // Each quad is its own glTF node, so its object id is 100 + node.
  for (uint32_t i = 0; i < s.instances.size(); ++i) s.instances[i].node = i;
  const view_camera cam = make_look_at_camera(dvec3(0, 0, 5), dvec3(0.0), dvec3(0, 1, 0), 30.0, size, size);
  return {render_image(s, accel, cam, settings)};
}

// The Cryptomatte coverage of id at pixel (x, y), 0 when not ranked.
float coverage_of(const film& f, int x, int y, uint32_t id) {
  const size_t depth = size_t(f.aovs.crypto_depth);
  for (size_t k = 0; k < depth; ++k) {
    const id_coverage& c = f.crypto_object[f.index(x, y) * depth + k];
    if (c.id == id && c.coverage > 0.0f) return c.coverage;
  }
  return 0.0f;
}

TEST(camera_alpha, one_blend_layer_over_nothing_has_its_own_alpha_and_premultiplied_colour) {
  const rendered r = render_layers({blend_emitter(2.0f, 0.3f)});
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const vec4 c = r.image.color[r.image.index(x, y)];
      ASSERT_NEAR(c.a, 0.3f, 1e-6f) << x << "," << y;  // it was 1: black baked in behind the glass
      ASSERT_NEAR(c.r, 0.3f * 2.0f, 1e-5f);            // premultiplied: alpha · radiance
      ASSERT_NEAR(coverage_of(r.image, x, y, 100), 0.3f, 1e-6f);
    }
}

TEST(camera_alpha, stacked_blend_layers_compose_like_over) {
  // A = 1 − (1 − 0.3)(1 − 0.5) = 0.65; the back layer covers (1 − 0.3)·0.5 = 0.35.
  const rendered r = render_layers({blend_emitter(1.0f, 0.3f), blend_emitter(4.0f, 0.5f)});
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const vec4 c = r.image.color[r.image.index(x, y)];
      ASSERT_NEAR(c.a, 0.65f, 1e-6f);
      ASSERT_NEAR(c.r, 0.3f * 1.0f + 0.35f * 4.0f, 1e-5f);
      const float front = coverage_of(r.image, x, y, 100), back = coverage_of(r.image, x, y, 101);
      ASSERT_NEAR(front, 0.3f, 1e-6f);
      ASSERT_NEAR(back, 0.35f, 1e-6f);
      ASSERT_NEAR(front + back, c.a, 1e-6f);  // the mattes sum to alpha
    }
}

TEST(camera_alpha, a_blend_layer_over_an_opaque_surface_is_opaque) {
  material back = testing::emitter(1.0f);
  const rendered r = render_layers({blend_emitter(2.0f, 0.25f), back});
  const vec4 c = r.image.color[r.image.index(8, 8)];
  EXPECT_FLOAT_EQ(c.a, 1.0f);
  EXPECT_NEAR(c.r, 0.25f * 2.0f + 0.75f * 1.0f, 1e-5f);
  EXPECT_NEAR(coverage_of(r.image, 8, 8, 100) + coverage_of(r.image, 8, 8, 101), 1.0f, 1e-6f);
}

TEST(camera_alpha, the_background_colour_is_not_seen_through_a_blend_layer_unless_shown) {
  // A red background behind the layer: hidden like the background of an empty pixel...
  const rendered hidden = render_layers({blend_emitter(0.0f, 0.4f)}, false, vec3(1, 0, 0));
  EXPECT_NEAR(hidden.alpha(3, 3), 0.4, 1e-6);
  EXPECT_EQ(hidden.image.color[hidden.image.index(3, 3)].r, 0.0f);
  // ...and seen, opaque, with --show-background.
  const rendered shown = render_layers({blend_emitter(0.0f, 0.4f)}, false, vec3(1, 0, 0), true);
  EXPECT_FLOAT_EQ(float(shown.alpha(3, 3)), 1.0f);
  EXPECT_NEAR(shown.image.color[shown.image.index(3, 3)].r, 0.6f, 1e-6f);
}

TEST(camera_alpha, glass_holds_out_by_default_and_passes_its_refraction_when_transparent) {
  // Thin-walled glass seen head-on: Fresnel reflects F(1.5) = 0.04 at normal incidence (a little
  // more off axis), the rest passes straight on into the background.
  const rendered opaque = render_layers({thin_glass()});
  const rendered clear = render_layers({thin_glass()}, true);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      ASSERT_FLOAT_EQ(float(opaque.alpha(x, y)), 1.0f);
      const double a = clear.alpha(x, y);
      ASSERT_GT(a, 0.039);
      ASSERT_LT(a, 0.045);
      ASSERT_NEAR(coverage_of(clear.image, x, y, 100), a, 1e-6);
    }
  // At the centre the view is within 2° of normal: A is the reflected share F, 1 − A the transmitted.
  EXPECT_NEAR(clear.alpha(8, 8), fresnel_dielectric(1.0f, 1.0f / 1.5f), 2e-4);
}

TEST(camera_alpha, glass_over_an_opaque_surface_stays_opaque_when_transparent) {
  const rendered r = render_layers({thin_glass(), testing::emitter(1.0f)}, true);
  EXPECT_FLOAT_EQ(float(r.alpha(8, 8)), 1.0f);
  EXPECT_NEAR(coverage_of(r.image, 8, 8, 100), 1.0f, 1e-6f);  // what glass shows is the glass's matte
}

}  // namespace
}  // namespace kiln
