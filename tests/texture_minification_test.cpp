// Texture minification: a fine checkerboard floor receding to the horizon, unlit, seen directly and
// through a planar mirror. Where one pixel covers many checker cells, a 1-spp render with ray-cone
// mip-mapping must match a supersampled reference (the pixel's true average), while the same
// texture with minFilter LINEAR (no mip) aliases far from it. Also: the ray cone after a mirror has
// the width of the unfolded straight ray, and the filtered image is identical for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "render/tile_renderer.h"
#include "render/view_camera.h"
#include "shade/surface.h"
#include "shade/whitted.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

constexpr int image_width = 256, image_height = 128, cell_texels = 4;
constexpr float cell = 0.025f;  // world size of one checker cell on the floor
constexpr float eye_height = 1.0f;
constexpr float floor_far = 400.0f;      // the floor ends this far from the eye (unfolded)
constexpr float mirror_distance = 3.0f;  // eye to mirror, mirror scene
constexpr int width = 128, height = 96;

// 4-texel black and white cells: sRGB 0 and 255 decode to exactly 0 and 1, so a pixel covering many
// cells averages to 0.5 (linear).
image checker_image() {
  image img;
  img.width = image_width;
  img.height = image_height;
  img.texels8.resize(size_t(image_width) * image_height * 4);
  for (int y = 0; y < image_height; ++y)
    for (int x = 0; x < image_width; ++x) {
      uint8_t v = ((x / cell_texels + y / cell_texels) & 1) ? 255 : 0;
      uint8_t* t = &img.texels8[(size_t(y) * image_width + x) * 4];
      t[0] = t[1] = t[2] = v;
      t[3] = 255;
    }
  return img;
}

// A horizontal floor y = 0 over [x0, x1] × [z0, z1], its UVs repeating the checker (one repeat spans
// image_width / cell_texels cells).
void add_floor(scene& s, float x0, float x1, float z0, float z1, uint32_t material) {
  mesh m;
  m.positions = {{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}};
  const float su = 1.0f / (cell * (image_width / cell_texels)),
              sv = 1.0f / (cell * (image_height / cell_texels));
  for (const vec3& p : m.positions) m.texcoords0.push_back({p.x * su, p.z * sv});
  m.indices = {0, 1, 2, 0, 2, 3};
  testing::add_mesh_instance(s, std::move(m), material);
}

// The floor (unlit checker, sampled by `mipmap`), seen straight down -z or, with a mirror, reflected
// by a vertical mirror at z = -mirror_distance while the floor lies behind the eye. The unfolded
// geometry is the same in both: the floor runs from under the eye to floor_far.
scene checker_scene(mip_mode mipmap, bool through_mirror) {
  scene s;
  s.images.push_back(checker_image());
  texture tex;
  tex.sampling.mipmap = mipmap;
  s.textures.push_back(tex);
  material floor_material;
  floor_material.unlit = true;
  floor_material.double_sided = true;
  floor_material.base_color_texture.texture = 0;
  s.materials.push_back(floor_material);
  if (!through_mirror) {
    add_floor(s, -floor_far, floor_far, -floor_far, 1.0f, 0);
    return s;
  }
  material mirror;
  mirror.metallic_factor = 1.0f;
  mirror.roughness_factor = 0.0f;
  mirror.double_sided = true;
  s.materials.push_back(mirror);
  const float zm = -mirror_distance;
  add_floor(s, -floor_far, floor_far, zm, floor_far - 2.0f * mirror_distance, 0);
  mesh m;
  m.positions = {
      {-floor_far, 0, zm}, {floor_far, 0, zm}, {floor_far, floor_far, zm}, {-floor_far, floor_far, zm}};
  m.indices = {0, 1, 2, 0, 2, 3};
  testing::add_mesh_instance(s, std::move(m), 1);
  return s;
}

view_camera checker_camera() {
  return make_look_at_camera(dvec3(0, eye_height, 0), dvec3(0, eye_height - 0.2, -1), dvec3(0, 1, 0), 30.0,
                             width, height);
}

film render(const scene& s, int spp, int threads = 1) {
  embree_accelerator accel(s);
  render_settings settings;
  settings.samples_per_pixel = spp;
  settings.threads = threads;
  return render_image(s, accel, checker_camera(), settings);
}

// Rows where every point of every pixel sees the floor (unfolded distance below floor_far, beyond
// the mirror) and one pixel spans at least two checker cells even across the ray (cone width there).
std::vector<int> minified_rows() {
  const view_camera cam = checker_camera();
  const double spread = camera_pixel_cone(cam).spread;
  std::vector<int> rows;
  for (int y = 0; y < height; ++y) {
    bool ok = true;
    for (double py : {double(y), y + 1.0})
      for (double px : {0.0, double(width)}) {
        const vec3 d = generate_camera_ray(cam, px, py).direction;
        if (!(d.y < 0.0f)) {
          ok = false;
          continue;
        }
        const double t = eye_height / -d.y;  // unfolded path length to the floor
        const double horizontal = t * std::sqrt(double(d.x) * d.x + double(d.z) * d.z);
        ok = ok && horizontal < 0.8 * floor_far && t * -d.z > 2.0 * mirror_distance &&
             spread * t >= 2.0 * cell;
      }
    if (ok) rows.push_back(y);
  }
  return rows;
}

double rms_difference(const film& a, const film& b, const std::vector<int>& rows) {
  double sum = 0.0;
  size_t n = 0;
  for (int y : rows)
    for (int x = 0; x < width; ++x) {
      const size_t i = a.index(x, y);
      const vec4 d = a.color[i] - b.color[i];
      sum += double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
      n += 3;
    }
  return std::sqrt(sum / double(n));
}

double mean_red(const film& f, const std::vector<int>& rows) {
  double sum = 0.0;
  for (int y : rows)
    for (int x = 0; x < width; ++x) sum += f.color[f.index(x, y)].r;
  return sum / double(rows.size() * width);
}

void expect_no_aliasing(bool through_mirror) {
  const std::vector<int> rows = minified_rows();
  ASSERT_GE(rows.size(), 8u);  // enough rows to measure
  // The reference: 64 spp, each sample's cone 1/8 pixel wide. It must agree with plain point
  // sampling at 64 spp (no mip), whose own noise is about 0.06 here, and average black and white to 0.5.
  const film reference = render(checker_scene(mip_mode::linear, through_mirror), 64);
  const film point_sampled = render(checker_scene(mip_mode::none, through_mirror), 64);
  EXPECT_NEAR(mean_red(reference, rows), 0.5, 0.01);
  EXPECT_NEAR(mean_red(point_sampled, rows), 0.5, 0.01);
  EXPECT_LT(rms_difference(reference, point_sampled, rows), 0.08);
  const film filtered = render(checker_scene(mip_mode::linear, through_mirror), 1);
  const film aliased = render(checker_scene(mip_mode::none, through_mirror), 1);
  // Mip levels average linear values (sRGB decoded first): black and white give 0.5, not sRGB 0.5.
  EXPECT_NEAR(mean_red(filtered, rows), 0.5, 0.01);
  const double filtered_rms = rms_difference(filtered, reference, rows);
  const double aliased_rms = rms_difference(aliased, reference, rows);
  std::printf("rows %d-%d (%zu): rms against the reference: mip-mapped 1 spp %.4f, no mip 1 spp %.4f\n",
              rows.front(), rows.back(), rows.size(), filtered_rms, aliased_rms);
  EXPECT_LT(filtered_rms, 0.05);
  EXPECT_GT(aliased_rms, 0.3);
}

TEST(texture_minification, horizon_checker_does_not_alias) { expect_no_aliasing(false); }

TEST(texture_minification, horizon_checker_through_planar_mirror_does_not_alias) { expect_no_aliasing(true); }

// The cone that leaves a planar mirror continues unchanged: at the floor its width, and so the UV
// footprint built from it, equals that of the straight ray from the mirrored eye.
TEST(texture_minification, cone_after_planar_mirror_matches_unfolded_straight_ray) {
  const scene s = checker_scene(mip_mode::linear, true);
  embree_accelerator accel(s);
  const view_camera cam = checker_camera();
  const ray_cone camera_cone{0.0f, float(camera_pixel_cone(cam).spread)};
  const ray eye_ray = generate_camera_ray(cam, 0.3 * width, 0.2 * height);

  std::optional<hit> on_mirror = accel.intersect(eye_ray);
  ASSERT_TRUE(on_mirror && s.instances[on_mirror->instance_id].material == 1);
  const surface_point mirror_point = make_surface_point(s, *on_mirror, eye_ray);
  const ray_cone leaving = reflected_cone(cone_at(camera_cone, on_mirror->t));
  ray bounced;
  bounced.direction = glm::reflect(eye_ray.direction, mirror_point.geometric_normal);
  bounced.origin = mirror_point.position;
  bounced.tmin = 1e-4f;
  std::optional<hit> on_floor = accel.intersect(bounced);
  ASSERT_TRUE(on_floor && s.instances[on_floor->instance_id].material == 0);
  const ray_cone arriving = cone_at(leaving, on_floor->t);
  const surface_point folded = make_surface_point(s, *on_floor, bounced, arriving.width);

  // The mirrored eye sees the same floor point along one straight line of the same total length.
  const vec3 floor_point = folded.position;
  const vec3 mirrored_eye =
      vec3(eye_ray.origin.x, eye_ray.origin.y, -2.0f * mirror_distance - eye_ray.origin.z);
  const float straight_length = glm::length(floor_point - mirrored_eye);
  EXPECT_NEAR(arriving.width, camera_cone.spread * straight_length, 1e-4f * arriving.width);
  ray straight;
  straight.origin = mirrored_eye;
  straight.direction = glm::normalize(floor_point - mirrored_eye);
  // Start past the mirror plane (the mirrored eye sits behind the mirror).
  straight.tmin = 1.001f * (-mirror_distance - mirrored_eye.z) / straight.direction.z;
  std::optional<hit> direct = accel.intersect(straight);
  ASSERT_TRUE(direct && s.instances[direct->instance_id].material == 0);
  const surface_point unfolded =
      make_surface_point(s, *direct, straight, cone_at(camera_cone, direct->t).width);
  // Same ellipse: axes equal (the across axis may flip sign with the mirrored handedness).
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(std::abs(folded.footprint0.dx[k]), std::abs(unfolded.footprint0.dx[k]),
                1e-3f * glm::length(unfolded.footprint0.dx));
    EXPECT_NEAR(std::abs(folded.footprint0.dy[k]), std::abs(unfolded.footprint0.dy[k]),
                1e-3f * glm::length(unfolded.footprint0.dy));
  }
  EXPECT_GT(glm::length(unfolded.footprint0.dx), 0.0f);
}

// The pyramids are built on the render's threads and read by all of them; the filtered image must
// not depend on how many there are.
TEST(texture_minification, mip_mapped_render_is_identical_for_any_thread_count) {
  const scene s = checker_scene(mip_mode::linear, true);
  const film one = render(s, 2, 1);
  const film many = render(s, 2, 4);
  const film three = render(s, 2, 3);
  ASSERT_EQ(one.color.size(), many.color.size());
  EXPECT_EQ(std::memcmp(one.color.data(), many.color.data(), one.color.size() * sizeof(vec4)), 0);
  EXPECT_EQ(std::memcmp(one.color.data(), three.color.data(), one.color.size() * sizeof(vec4)), 0);
}

}  // namespace
}  // namespace kiln
