// NaN and infinity never reach the image: a sample whose radiance is not finite (an infinite
// emission, a NaN environment) is discarded and counted, and its pixel averages the samples that
// remain. Z keeps +inf where nothing was hit, the one intended non-finite value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "accel/embree/embree_accelerator.h"
#include "render/tile_renderer.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

constexpr int image_size = 24;
const vec3 unlit_colour(0.25f, 0.5f, 0.75f);

// A quad [-0.6, 0.4]² at z = 0 facing the camera at z = 3: part of the image sees it, the rest
// sees the environment, and pixels on its edges see both.
scene quad_scene(const material& m) {
  scene s;
  s.materials.push_back(m);
  testing::add_quad(s, -0.6f, -0.6f, 0.4f, 0.4f, 0.0f, 0);
  return s;
}

view_camera front_camera() {
  return make_look_at_camera(dvec3(0, 0, 3), dvec3(0.0), dvec3(0, 1, 0), 40.0, image_size, image_size);
}

film render(const scene& s, int spp, bool show_background, render_statistics& stats) {
  embree_accelerator accel(s);
  render_settings settings;
  settings.samples_per_pixel = spp;
  settings.threads = 2;
  settings.tile_size = 8;
  settings.show_background = show_background;
  return render_image(s, accel, front_camera(), settings, &stats);
}

bool finite(const vec4& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && std::isfinite(c.a);
}

TEST(NonFiniteSamples, InfiniteEmissionIsDiscardedAndCounted) {
  material hot;
  hot.emissive_factor = vec3(std::numeric_limits<float>::infinity());
  const scene s = quad_scene(hot);
  render_statistics stats;
  const film image = render(s, 1, false, stats);
  // With one sample a pixel, every pixel that saw the quad (finite Z) lost its only sample.
  uint64_t hit_pixels = 0;
  for (size_t i = 0; i < image.color.size(); ++i) {
    ASSERT_TRUE(finite(image.color[i])) << "pixel " << i;
    ASSERT_TRUE(is_finite(image.vec3_layer(aov::normal)[i])) << "pixel " << i;
    if (std::isfinite(image.depth[i])) {
      ++hit_pixels;
      EXPECT_EQ(image.color[i], vec4(0.0f)) << "pixel " << i;
    } else {
      EXPECT_EQ(image.depth[i], std::numeric_limits<float>::infinity()) << "background Z is +inf";
    }
  }
  EXPECT_GT(hit_pixels, 50u);
  EXPECT_LT(hit_pixels, uint64_t(image_size * image_size));
  EXPECT_EQ(stats.discarded_samples, hit_pixels);
}

// Samples near the float maximum are finite and kept; their sum over 16 samples is not a float,
// so the pixel must average them without overflowing to +inf.
TEST(NonFiniteSamples, VeryBrightSamplesAreKeptAndAveragedWithoutOverflow) {
  material bright;
  bright.unlit = true;
  bright.base_color_factor = vec4(3e38f, 2e38f, 1.0f, 1.0f);
  const scene s = quad_scene(bright);
  render_statistics stats;
  const film image = render(s, 16, false, stats);
  EXPECT_EQ(stats.discarded_samples, 0u);
  size_t inside = 0;
  for (size_t i = 0; i < image.color.size(); ++i) {
    ASSERT_TRUE(finite(image.color[i])) << "pixel " << i;
    if (image.color[i].a != 1.0f) continue;  // edge and background pixels average in zeros
    ++inside;
    EXPECT_FLOAT_EQ(image.color[i].r, 3e38f) << "pixel " << i;
    EXPECT_FLOAT_EQ(image.color[i].g, 2e38f) << "pixel " << i;
  }
  EXPECT_GT(inside, 50u);
}

// The same quad, unlit, against a NaN environment shown as background: each pixel keeps exactly
// its quad samples, so its colour is the quad's with alpha 1, and the count of discarded samples
// is every background sample, which a reference render with a finite environment measures as
// (1 - alpha) · spp per pixel.
TEST(NonFiniteSamples, NanEnvironmentSamplesAreDiscardedAndPixelsAverageTheRest) {
  constexpr int spp = 16;
  material flat;
  flat.unlit = true;
  flat.base_color_factor = vec4(unlit_colour, 1.0f);
  scene s = quad_scene(flat);

  render_statistics reference_stats;
  const film reference = render(s, spp, false, reference_stats);
  EXPECT_EQ(reference_stats.discarded_samples, 0u);

  s.env.color = vec3(std::numeric_limits<float>::quiet_NaN());
  render_statistics stats;
  const film image = render(s, spp, true, stats);

  uint64_t background_samples = 0, edge_pixels = 0;
  for (size_t i = 0; i < image.color.size(); ++i) {
    ASSERT_TRUE(finite(image.color[i])) << "pixel " << i;
    const float coverage = reference.color[i].a;  // fraction of samples that hit the quad
    background_samples += uint64_t(std::lround((1.0f - coverage) * spp));
    if (coverage > 0.0f && coverage < 1.0f) ++edge_pixels;
    if (coverage > 0.0f) {
      EXPECT_NEAR(image.color[i].r, unlit_colour.r, 1e-6f) << "pixel " << i;
      EXPECT_NEAR(image.color[i].g, unlit_colour.g, 1e-6f) << "pixel " << i;
      EXPECT_NEAR(image.color[i].b, unlit_colour.b, 1e-6f) << "pixel " << i;
      EXPECT_FLOAT_EQ(image.color[i].a, 1.0f) << "pixel " << i;
    } else {
      EXPECT_EQ(image.color[i], vec4(0.0f)) << "pixel " << i;
    }
    EXPECT_EQ(image.depth[i], reference.depth[i]) << "pixel " << i;
  }
  EXPECT_GT(edge_pixels, 0u) << "the quad's edges must split pixels for this test to mean anything";
  EXPECT_GT(stats.discarded_samples, 0u);
  EXPECT_EQ(stats.discarded_samples, background_samples);
}

}  // namespace
}  // namespace kiln
