// Image tests on analytic primitives: the quadric showcase (every kind) renders with no NaN, each
// primitive covers pixels, and 1 and N threads give identical bytes; a sphere's silhouette covers
// exactly the analytic disk area, within one pixel row.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/tile_renderer.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

const std::string showcase = std::string(KILN_SOURCE_DIR) + "/scenes/quadric_showcase.gltf";

film render(const scene& world, const accelerator& accel, const view_camera& cam, int threads, int tile) {
  render_settings settings;
  settings.threads = threads;
  settings.tile_size = tile;
  return render_image(world, accel, cam, settings);
}

TEST(quadric_image, showcase_has_every_kind_no_nan_and_is_thread_independent) {
  scene world = load_gltf(showcase);
  ASSERT_FALSE(world.cameras.empty());
  std::vector<bool> kinds_present(9, false);
  for (const quadric& q : world.quadrics) kinds_present[size_t(q.kind)] = true;
  for (size_t k = 0; k < kinds_present.size(); ++k) EXPECT_TRUE(kinds_present[k]) << "kind " << k;

  embree_accelerator accel(world);
  view_camera cam = make_gltf_camera(world.cameras[0], 192, 108);
  film one = render(world, accel, cam, 1, 16);
  film many = render(world, accel, cam, 3, 7);
  ASSERT_EQ(one.color.size(), many.color.size());
  EXPECT_EQ(std::memcmp(one.color.data(), many.color.data(), one.color.size() * sizeof(vec4)), 0);
  EXPECT_EQ(std::memcmp(one.vec3_layer(aov::normal).data(), many.vec3_layer(aov::normal).data(),
                        one.vec3_layer(aov::normal).size() * sizeof(vec3)),
            0);
  for (size_t i = 0; i < one.color.size(); ++i) {
    ASSERT_TRUE(is_finite(one.color[i])) << "pixel " << i;
    ASSERT_TRUE(is_finite(one.vec3_layer(aov::normal)[i])) << "pixel " << i;
  }
  // Every placed primitive is visible: count camera rays that hit each instance first.
  std::vector<int> pixels(world.instances.size(), 0);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (auto h = accel.intersect(generate_camera_ray(cam, x + 0.5, y + 0.5))) ++pixels[h->instance_id];
  for (size_t i = 0; i < pixels.size(); ++i)
    EXPECT_GT(pixels[i], 30) << "instance " << i << " (node " << world.instances[i].node << ")";
}

// A sphere of radius r at distance D on the optical axis subtends the half-angle asin(r/D); on the
// image plane its silhouette is a disk of radius (H/2)·tan(asin(r/D))/tan(fov/2) pixels.
TEST(quadric_image, sphere_coverage_equals_the_analytic_disk_area) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    testing::gltf_builder b;
    b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});  // unplaced; the builder needs a buffer
    b.doc["extensionsUsed"] = {"KILN_quadric"};
    b.doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", "sphere"}, {"radius", 1.0}}};
    b.add_node({{"scale", {scale, scale, scale}}, {"extensions", {{"KILN_quadric", {{"primitive", 0}}}}}});
    std::string file = testing::scratch_folder("coverage") + "/sphere.gltf";
    b.write(file);
    scene world = load_gltf(file);
    embree_accelerator accel(world);
    const int size = 201;
    const double fov = 30.0, distance = 6.0 * scale;
    view_camera cam = make_look_at_camera(dvec3(0, 0, distance), dvec3(0.0), dvec3(0, 1, 0), fov, size, size);
    film image = render(world, accel, cam, 2, 32);
    double covered = 0.0;
    for (const vec4& c : image.color) covered += c.a;
    const double radius_px =
        0.5 * size * std::tan(std::asin(scale / distance)) / std::tan(glm::radians(fov) / 2.0);
    const double expected = pi * radius_px * radius_px;
    EXPECT_NEAR(covered, expected, 2.0 * radius_px)
        << "scale " << scale << ", disk radius " << radius_px << " px";
    EXPECT_GT(radius_px, 40.0);
  }
}

}  // namespace
}  // namespace kiln
