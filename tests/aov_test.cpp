// The nearest-sample AOVs on a whole render: position, albedo and ids of known objects, never
// filtered, and the same bytes for any thread count.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/aov_table.h"
#include "render/tile_renderer.h"
#include "shade/path_record.h"
#include "support/gltf_builder.h"

namespace kiln {
namespace {

constexpr int width = 48, height = 32;

view_camera test_camera() {
  return make_look_at_camera(dvec3(0.3, 0.2, 5), dvec3(0.0), dvec3(0, 1, 0), 40.0, width, height);
}

// Two quads facing the camera: node 1 (material 1, base colour 0.2 0.5 0.8) on z = 0 covering
// x < 0, node 2 (material 2) on z = -1 covering x > 0. Node 0 is an empty node and material 0 is
// unused, so node, material and instance numbers differ. Node 3, without a material, sits on z = 0.5
// in the top-left corner: the default material, whose id is one past the file's three.
scene two_quads() {
  testing::gltf_builder b;
  b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 0.0, 1.0}}}}});
  int blue = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.5, 0.8, 1.0}}}}});
  int red = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.1, 0.3, 1.0}}}}});
  b.add_node({{"name", "empty"}});
  b.add_node(
      {{"mesh", b.add_mesh({{-3, -3, 0}, {0, -3, 0}, {0, 3, 0}, {-3, 3, 0}}, {0, 1, 2, 0, 2, 3}, blue)}});
  b.add_node(
      {{"mesh", b.add_mesh({{0, -3, -1}, {3, -3, -1}, {3, 3, -1}, {0, 3, -1}}, {0, 1, 2, 0, 2, 3}, red)}});
  b.add_node({{"mesh", b.add_mesh({{-3, 1, 0.5}, {-1.5, 1, 0.5}, {-1.5, 3, 0.5}, {-3, 3, 0.5}},
                                  {0, 1, 2, 0, 2, 3})}});
  auto path = std::filesystem::temp_directory_path() / ("kiln_aov_" + std::to_string(::getpid()) + ".gltf");
  b.write(path.string());
  return load_gltf(path.string());
}

aov_set every_aov() {
  return aov_set_of({aov::beauty, aov::depth, aov::normal, aov::position, aov::albedo, aov::uv, aov::ids});
}

film render(const scene& world, int threads, int spp, const aov_set& aovs = every_aov()) {
  embree_accelerator accel(world);
  render_settings s;
  s.threads = threads;
  s.samples_per_pixel = spp;
  s.filter = {filter_kind::gaussian, 1.5f};  // reaches the neighbours: the AOVs must still not blend
  s.tile_size = 8;
  s.aovs = aovs;
  return render_image(world, accel, test_camera(), s);
}

uint32_t instance_of_node(const scene& world, uint32_t node) {
  for (uint32_t i = 0; i < world.instances.size(); ++i)
    if (world.instances[i].node == node) return i;
  ADD_FAILURE() << "no instance of node " << node;
  return 0;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(aov, only_requested_buffers_exist) {
  scene world = two_quads();
  film f = render(world, 1, 1, aov_set{});
  EXPECT_EQ(f.depth.size(), size_t(width * height));
  EXPECT_EQ(f.vec3_layer(aov::normal).size(), size_t(width * height));
  EXPECT_TRUE(f.vec3_layer(aov::position).empty() && f.vec3_layer(aov::albedo).empty() && f.uv.empty() &&
              f.ids.empty());
  const aov_set ids_only = aov_set_of({aov::ids});
  f = render(world, 1, 1, ids_only);
  EXPECT_TRUE(f.depth.empty() && f.vec3_layer(aov::normal).empty() && f.vec3_layer(aov::position).empty());
  EXPECT_EQ(f.ids.size(), size_t(width * height));
}

// Shading files a filtered AOV of three floats in the sample's camera_passes, which keep one colour
// per AOV from aov::direct on: a row before it would have nowhere to be recorded.
TEST(aov, every_filtered_triple_has_a_camera_pass_slot) {
  int slots = 0;
  for (const aov_row& row : aov_table) {
    if (row.shape != aov_shape::triple || row.sampling != aov_sampling::filtered) continue;
    EXPECT_GE(int(row.id), first_pass) << row.name;
    EXPECT_LT(int(row.id) - first_pass, pass_count) << row.name;
    ++slots;
  }
  EXPECT_GE(slots, 7);  // the light split, albedo_filtered, N_filtered, diffuse, specular
  camera_passes p;
  p.value(aov::specular) = vec3(1.0f, 2.0f, 3.0f);
  p.value(aov::direct) += vec3(0.5f);
  EXPECT_EQ(p.value(aov::specular), vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(p.value(aov::direct), vec3(0.5f));
  EXPECT_EQ(p.value(aov::diffuse), vec3(0.0f));
  p.clear();
  EXPECT_EQ(p.value(aov::specular), vec3(0.0f));
}

TEST(aov, position_is_the_camera_ray_hit_point) {
  scene world = two_quads();
  film f = render(world, 2, 1);  // one sample at each pixel centre
  const view_camera cam = test_camera();
  int checked = 0;
  for (int y = 0; y < height; y += 3)
    for (int x = 0; x < width; x += 5) {
      size_t i = f.index(x, y);
      if (std::isinf(f.depth[i])) continue;
      ray r = generate_camera_ray(cam, x + 0.5, y + 0.5);
      dvec3 expected = dvec3(r.origin) + double(f.depth[i]) * glm::normalize(dvec3(r.direction));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(f.vec3_layer(aov::position)[i][c], expected[c], 1e-4 * f.depth[i]) << x << "," << y;
      // Each quad is a plane of constant z.
      const float z = f.vec3_layer(aov::position)[i].z;
      EXPECT_NEAR(z,
                  z > 0.25f                                 ? 0.5f
                  : f.vec3_layer(aov::position)[i].x < 0.0f ? 0.0f
                                                            : -1.0f,
                  1e-5)
          << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 20);
}

TEST(aov, albedo_and_ids_name_the_object_hit_and_background_is_minus_one) {
  scene world = two_quads();
  film f = render(world, 2, 4);
  const uint32_t left = instance_of_node(world, 1), right = instance_of_node(world, 2);
  int seen_left = 0, seen_right = 0, seen_background = 0, seen_default = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      size_t i = f.index(x, y);
      const glm::ivec3 id = f.ids[i];
      if (std::isinf(f.depth[i])) {
        EXPECT_EQ(id, glm::ivec3(-1)) << x << "," << y;
        EXPECT_EQ(f.vec3_layer(aov::albedo)[i], vec3(0.0f));
        ++seen_background;
      } else if (f.vec3_layer(aov::position)[i].z > 0.25f) {
        EXPECT_EQ(id, glm::ivec3(3, 3, int(instance_of_node(world, 3)))) << x << "," << y;
        EXPECT_EQ(f.vec3_layer(aov::albedo)[i], vec3(1.0f));
        ++seen_default;
      } else if (f.vec3_layer(aov::position)[i].x < 0.0f) {
        EXPECT_EQ(id, glm::ivec3(1, 1, int(left))) << x << "," << y;
        EXPECT_EQ(f.vec3_layer(aov::albedo)[i], vec3(0.2f, 0.5f, 0.8f)) << x << "," << y;
        ++seen_left;
      } else {
        EXPECT_EQ(id, glm::ivec3(2, 2, int(right))) << x << "," << y;
        EXPECT_EQ(f.vec3_layer(aov::albedo)[i], vec3(0.9f, 0.1f, 0.3f)) << x << "," << y;
        ++seen_right;
      }
    }
  EXPECT_GT(seen_left, 50);
  EXPECT_GT(seen_right, 50);
  EXPECT_GT(seen_background, 10);
  EXPECT_GT(seen_default, 10);
  EXPECT_NE(left, right);
}

TEST(aov, nearest_sample_aovs_do_not_depend_on_threads) {
  scene world = two_quads();
  film one = render(world, 1, 4), many = render(world, 3, 4);
  EXPECT_TRUE(same_bytes(one.color, many.color));
  EXPECT_TRUE(same_bytes(one.vec3_layer(aov::position), many.vec3_layer(aov::position)));
  EXPECT_TRUE(same_bytes(one.vec3_layer(aov::albedo), many.vec3_layer(aov::albedo)));
  EXPECT_TRUE(same_bytes(one.uv, many.uv));
  EXPECT_TRUE(same_bytes(one.ids, many.ids));
}

}  // namespace
}  // namespace kiln
