// EXT_mesh_gpu_instancing through Embree: a file whose one node places a quad many times loads
// as one mesh plus one instance per glTF instance, and every ray hit names the instance whose
// transform it struck (Embree's instID maps back to scene.instances).
#include <gtest/gtest.h>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// A unit quad in z = 0 (front face +z) placed once per translation by EXT_mesh_gpu_instancing,
// under a node that moves everything 5 units down -z.
std::string instanced_quads(const temp_folder& dir, const std::vector<float>& translations) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, k_ushort, "SCALAR", 1);
  const int mesh_index = b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  const int t = b.add_data(translations, k_float, "VEC3", 3);
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.set_scene(
      {b.add_node({{"mesh", mesh_index},
                   {"translation", {0, 0, -5}},
                   {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", t}}}}}}}})});
  const std::string path = dir.file("quads.glb");
  write_bytes(path, b.glb_bytes());
  return path;
}

ray down_z(float x, float y) {
  ray r;
  r.origin = {x, y, 0.0f};
  r.direction = {0, 0, -1};
  return r;
}

TEST(embree_gpu_instancing, hits_report_the_instance_they_strike) {
  temp_folder dir;
  // Three quads side by side in x, the middle one further away.
  const scene s = load_gltf(instanced_quads(dir, {0, 0, 0, 2, 0, -1, 4, 0, 0}));
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 3u);
  embree_accelerator accel(s);
  const float expected_t[3] = {5.0f, 6.0f, 5.0f};
  for (uint32_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    auto h = accel.intersect(down_z(2.0f * i + 0.25f, 0.75f));
    ASSERT_TRUE(h);
    EXPECT_EQ(h->instance_id, i);
    EXPECT_NEAR(h->t, expected_t[i], 1e-5f);
    EXPECT_NEAR(h->geometric_normal.z, 1.0f, 1e-6f);
  }
  EXPECT_FALSE(accel.intersect(down_z(1.5f, 0.5f)));  // the gap between instances 0 and 1
}

TEST(embree_gpu_instancing, hundred_thousand_instances_of_one_mesh) {
  temp_folder dir;
  constexpr size_t side = 400, rows = 250;  // 100,000 quads on a grid with pitch 2
  std::vector<float> translations;
  translations.reserve(side * rows * 3);
  for (size_t y = 0; y < rows; ++y)
    for (size_t x = 0; x < side; ++x) translations.insert(translations.end(), {2.0f * x, 2.0f * y, 0.0f});
  const scene s = load_gltf(instanced_quads(dir, translations));
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), side * rows);
  embree_accelerator accel(s);
  for (size_t id : {size_t(0), size_t(401), size_t(54321), side * rows - 1}) {
    SCOPED_TRACE(id);
    const float x = 2.0f * static_cast<float>(id % side) + 0.5f,
                y = 2.0f * static_cast<float>(id / side) + 0.5f;
    auto h = accel.intersect(down_z(x, y));
    ASSERT_TRUE(h);
    EXPECT_EQ(h->instance_id, id);
    EXPECT_NEAR(h->t, 5.0f, 1e-4f);
  }
}

}  // namespace
}  // namespace kiln
