// Far from the origin (issue 14 item 6): a scene translated by 1e4 or 1e6 must render like the
// same scene at the origin. Geometry handed to a backend in world-space floats loses its detail
// there (a float at 1e6 has a spacing of 0.0625) and the triangle error bounds grow with the
// distance, so shadows change shape. kiln traces in camera-relative render space, so the
// distance never reaches the floats. The scene: a quadric sphere of radius 0.5 at height 1 over a
// plane, a point light at height 2 straight above, an orthographic camera looking down. The
// sphere's shadow is the ring between the sphere's outline (radius 0.5) and radius
// 2·tan(30°) = 1.1547 on the plane; its pixels are counted against the pixel centres inside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "accel/make_accelerator.h"
#include "job/render_job.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using nlohmann::json;

constexpr int image_side = 96;
constexpr double half_view = 1.5;  // xmag = ymag: 3 units over 96 pixels, 1/32 a pixel
constexpr double sphere_radius = 0.5;
const double shadow_radius = 2.0 * std::tan(std::asin(sphere_radius / 1.0));  // light 1 above the centre
constexpr int plane_node = 1;

// The scene with everything under one root node translated by `offset`.
std::string write_scene(double offset, const std::string& name) {
  testing::gltf_builder b;
  const int white = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
  const int plane =
      b.add_mesh({{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}, {0, 1, 2, 0, 2, 3}, white);
  b.doc["extensionsUsed"] = {"KILN_quadric"};
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {json{{"kind", "sphere"}, {"radius", sphere_radius}}};
  const int root = b.add_node({{"name", "root"}, {"translation", {offset, offset, offset}}});
  const int plane_index = b.add_node({{"name", "plane"}, {"mesh", plane}});
  EXPECT_EQ(plane_index, plane_node);
  const int sphere =
      b.add_node({{"name", "sphere"},
                  {"translation", {0.0, 0.0, 1.0}},
                  {"extensions", {{"KILN_quadric", {{"primitive", 0}, {"material", white}}}}}});
  const int light = b.add_light({{"type", "point"}, {"intensity", 10.0}});
  const int lamp = b.add_node({{"name", "lamp"},
                               {"translation", {0.0, 0.0, 2.0}},
                               {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
  b.add_camera(
      {{"type", "orthographic"},
       {"orthographic", {{"xmag", half_view}, {"ymag", half_view}, {"znear", 0.01}, {"zfar", 100.0}}}});
  const int eye = b.add_node({{"name", "eye"}, {"camera", 0}, {"translation", {0.0, 0.0, 5.0}}});
  for (int child : {plane_index, sphere, lamp, eye}) b.add_child(root, child);
  const std::string file = testing::scratch_folder("far_" + name) + "/scene.gltf";
  b.write(file);
  return file;
}

film render_scene(double offset, const std::string& name, const char* accel) {
  render_options o;
  o.input = write_scene(offset, name);
  o.width = image_side;
  o.height = image_side;
  o.quiet = true;
  o.lighting = "file";  // the file's light alone: its closed form, no sampled environment
  o.spp_given = 1;
  o.aovs.set(aov::ids);
  o.aovs.set(aov::position);
  const prepared_scene p = prepare_scene(o);
  const std::unique_ptr<accelerator> a = make_accelerator(p.world, *parse_accel_kind(accel));
  return render_image(p.world, *a, p.cam, make_render_settings(o));
}

// Pixels that see the plane in shadow (no light: radiance exactly 0).
int shadow_pixels(const film& f) {
  int n = 0;
  for (size_t i = 0; i < f.color.size(); ++i) n += f.ids[i].x == plane_node && f.color[i].r == 0.0f;
  return n;
}

// Pixel centres inside the visible shadow ring: outside the sphere's outline, inside the shadow.
int analytic_shadow_pixels() {
  int n = 0;
  for (int y = 0; y < image_side; ++y)
    for (int x = 0; x < image_side; ++x) {
      const double px = (x + 0.5) / image_side * 2.0 * half_view - half_view;
      const double py = half_view - (y + 0.5) / image_side * 2.0 * half_view;
      const double rho = std::hypot(px, py);
      n += rho > sphere_radius && rho < shadow_radius;
    }
  return n;
}

// Pixels whose colour differs by more than 1e-3 relative to the brighter of the two.
int changed_pixels(const film& a, const film& b) {
  int n = 0;
  for (size_t i = 0; i < a.color.size(); ++i) {
    const vec4 d = glm::abs(a.color[i] - b.color[i]);
    const float scale = std::max({1e-6f, a.color[i].r, b.color[i].r});
    n += std::max({d.r, d.g, d.b, d.a}) > 1e-3f * scale;
  }
  return n;
}

TEST(stability_far_from_origin, a_translated_scene_renders_like_the_scene_at_the_origin) {
  const int analytic = analytic_shadow_pixels();
  for (const char* accel : {"embree", "grid"}) {
    const film at_origin = render_scene(0.0, std::string("origin_") + accel, accel);
    const int shadow_at_origin = shadow_pixels(at_origin);
    // Pixels whose centre lies within about a pixel of the ring's edges may go either way.
    EXPECT_NEAR(shadow_at_origin, analytic, 0.01 * analytic) << accel;
    for (double offset : {1e4, 1e6, 3333333.3}) {  // the last not a float
      const film far =
          render_scene(offset, std::string("far_") + accel + std::to_string(int64_t(offset)), accel);
      const int changed = changed_pixels(at_origin, far);
      const int shadow = shadow_pixels(far);
      std::printf("%s offset %.10g: %d of %d pixels changed; shadow %d px (origin %d, analytic %d)\n", accel,
                  offset, changed, image_side * image_side, shadow, shadow_at_origin, analytic);
      // Translation leaves only rounding in the camera-relative space: at most 0.1% of pixels
      // (edge pixels whose centre is within a rounding error of an outline).
      EXPECT_LE(changed, image_side * image_side / 1000) << accel << " offset " << offset;
      EXPECT_NEAR(shadow, shadow_at_origin, 0.002 * analytic) << accel << " offset " << offset;
      // P stays in world space: the hit at the origin moved by the offset, within float rounding there.
      const float tolerance = 4.0f * float(offset) * std::numeric_limits<float>::epsilon() + 1e-4f;
      for (size_t i = 0; i < far.vec3_layer(aov::position).size(); ++i)
        if (far.ids[i].x == plane_node && at_origin.ids[i].x == plane_node) {
          const vec3 expected = at_origin.vec3_layer(aov::position)[i] + vec3(float(offset));
          ASSERT_LE(glm::length(far.vec3_layer(aov::position)[i] - expected), tolerance)
              << accel << " pixel " << i;
        }
    }
  }
}

}  // namespace
}  // namespace kiln
