// Analytic image test: a diffuse plane lit by one point light, with an occluder casting a shadow.
// Every visible, unshadowed pixel must equal (albedo/π)·I·cosθ/r² within 1e-3 relative, every
// shadowed pixel must be exactly zero — at scene scales 1e-3, 1 and 1e4, which also proves that
// shadow rays never re-hit the surface they start on (no shadow acne at any scale).
#include <gtest/gtest.h>

#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/tile_renderer.h"
#include "support/gltf_builder.h"

namespace kiln {
namespace {

constexpr double albedo = 0.5;
constexpr double intensity = 4.0;  // candela at scale 1
const dvec3 light_position(0.3, -0.2, 2.0);
// The whole scene is tilted and moved so that no surface is axis-aligned or passes through the
// origin: the hit points then carry real rounding error, which is what makes acne possible.
const glm::dquat tilt = glm::angleAxis(glm::radians(35.0), glm::normalize(dvec3(1.0, 2.0, 0.5)));
const dvec3 shift(0.37, -1.21, 0.83);

// World from the test's unit frame at a given scale.
dmat4 world_from_unit(double scale) {
  return glm::translate(dmat4(1.0), shift * scale) * glm::mat4_cast(tilt) *
         glm::scale(dmat4(1.0), dvec3(scale));
}

const double occluder_x0 = -1.0, occluder_x1 = -0.4, occluder_y0 = -0.3, occluder_y1 = 0.3, occluder_z = 1.0;

// Writes the scene with everything scaled by `scale`: through a root node's scale, or baked into
// the vertex positions. The light intensity grows with scale² so irradiance stays the same.
std::string write_scene(double scale, bool scale_vertices) {
  testing::gltf_builder b;
  float v = scale_vertices ? float(scale) : 1.0f;
  int diffuse = b.add_material({{"pbrMetallicRoughness",
                                 {{"baseColorFactor", {albedo, albedo, albedo, 1.0}},
                                  {"metallicFactor", 0.0},
                                  {"roughnessFactor", 1.0}}},
                                {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}});
  b.doc["extensionsUsed"].push_back("KHR_materials_specular");
  int plane = b.add_mesh({{-2 * v, -2 * v, 0}, {2 * v, -2 * v, 0}, {2 * v, 2 * v, 0}, {-2 * v, 2 * v, 0}},
                         {0, 1, 2, 0, 2, 3}, diffuse);
  float x0 = float(occluder_x0) * v, x1 = float(occluder_x1) * v, y0 = float(occluder_y0) * v,
        y1 = float(occluder_y1) * v, z = float(occluder_z) * v;
  int occluder =
      b.add_mesh({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, {0, 1, 2, 0, 2, 3}, diffuse);
  double node_scale = scale_vertices ? 1.0 : scale;
  dvec3 t = shift * scale;
  int root = b.add_node({{"scale", {node_scale, node_scale, node_scale}},
                         {"rotation", {tilt.x, tilt.y, tilt.z, tilt.w}},
                         {"translation", {t.x, t.y, t.z}}});
  b.add_child(root, b.add_node({{"mesh", plane}}));
  b.add_child(root, b.add_node({{"mesh", occluder}}));
  int light = b.add_light({{"type", "point"}, {"intensity", intensity * scale * scale}});
  dvec3 lp = transform_point(world_from_unit(scale), light_position);
  b.add_node(
      {{"translation", {lp.x, lp.y, lp.z}}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
  auto path = std::filesystem::temp_directory_path() /
              ("kiln_analytic_" + std::to_string(::getpid()) + "_" + std::to_string(scale) + ".gltf");
  b.write(path.string());
  return path.string();
}

bool inside(double x, double y, double margin) {
  return x > occluder_x0 - margin && x < occluder_x1 + margin && y > occluder_y0 - margin &&
         y < occluder_y1 + margin;
}

void check_scale(double scale, bool scale_vertices) {
  scene world = load_gltf(write_scene(scale, scale_vertices));
  ASSERT_EQ(world.lights.size(), 1u);
  embree_accelerator accel(world);
  const int size = 96;
  const dmat4 world_from = world_from_unit(scale);
  const dmat4 unit_from = glm::inverse(world_from);
  view_camera cam = make_look_at_camera(transform_point(world_from, dvec3(0, 0, 5)),
                                        transform_point(world_from, dvec3(0.0)),
                                        transform_vector(world_from, dvec3(0, 1, 0)), 50.0, size, size);
  render_settings settings;
  settings.threads = 2;
  film image = render_image(world, accel, cam, settings);

  int lit = 0, shadowed = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // The camera ray through the pixel centre, intersected with the plane z = 0 in unit space.
      ray r = generate_camera_ray(cam, x + 0.5, y + 0.5);
      dvec3 o = transform_point(unit_from, dvec3(r.origin));
      dvec3 d = glm::normalize(transform_vector(unit_from, dvec3(r.direction)));
      double t = -o.z / d.z;
      dvec3 p = o + t * d;
      if (std::abs(p.x) > 1.98 || std::abs(p.y) > 1.98) continue;  // near or beyond the plane's edge
      // Skip pixels that see the occluder, or whose point is near the shadow's boundary.
      dvec3 at_occluder_from_camera = o + (-(o.z - occluder_z) / d.z) * d;
      if (inside(at_occluder_from_camera.x, at_occluder_from_camera.y, 0.05)) continue;
      dvec3 to_light = light_position - p;
      dvec3 at_occluder_from_point = p + (occluder_z / to_light.z) * to_light;
      float value = image.color[image.index(x, y)].r;
      if (inside(at_occluder_from_point.x, at_occluder_from_point.y, -0.05)) {
        EXPECT_EQ(value, 0.0f) << "pixel " << x << "," << y << " should be in shadow at scale " << scale;
        ++shadowed;
        continue;
      }
      if (inside(at_occluder_from_point.x, at_occluder_from_point.y, 0.05)) continue;
      double r2 = glm::dot(to_light, to_light);
      double cos_theta = to_light.z / std::sqrt(r2);
      double expected = albedo / double(pi) * intensity * cos_theta / r2;
      EXPECT_NEAR(value / expected, 1.0, 1e-3) << "pixel " << x << "," << y << " at scale " << scale;
      ++lit;
    }
  // The checks above must have covered a real share of the image in both regions.
  EXPECT_GT(lit, size * size / 3);
  EXPECT_GT(shadowed, 100);
}

TEST(analytic_image, diffuse_plane_matches_closed_form_at_unit_scale) { check_scale(1.0, false); }
TEST(analytic_image, no_shadow_acne_at_millimetre_scale) { check_scale(1e-3, false); }
TEST(analytic_image, no_shadow_acne_at_ten_kilometre_scale) { check_scale(1e4, false); }
TEST(analytic_image, no_shadow_acne_with_large_vertex_coordinates) { check_scale(1e4, true); }

}  // namespace
}  // namespace kiln
