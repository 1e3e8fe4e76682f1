// gltf_sequence against load_gltf: each frame posed from the last (rigid meshes, materials and
// images handed over, deformed meshes built again) must equal a fresh load at that time, also
// after a frame that failed halfway, and a long sequence must not grow the memory budget frame by
// frame.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"
#include "support/animated_gltf.h"

namespace kiln {
namespace {

std::string shared_asset(const std::string& path) { return std::string(KILN_SHARED_ASSETS) + "/" + path; }

void expect_same_meshes(const scene& a, const scene& b) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    SCOPED_TRACE(m);
    EXPECT_EQ(a.meshes[m].positions, b.meshes[m].positions);
    EXPECT_EQ(a.meshes[m].normals, b.meshes[m].normals);
    EXPECT_EQ(a.meshes[m].indices, b.meshes[m].indices);
    EXPECT_EQ(a.meshes[m].texcoords0, b.meshes[m].texcoords0);
    EXPECT_EQ(a.meshes[m].tangents, b.meshes[m].tangents);
  }
}

void expect_same_placements(const scene& a, const scene& b) {
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].shape, b.instances[i].shape);
    EXPECT_EQ(a.instances[i].material, b.instances[i].material);
    EXPECT_EQ(a.instances[i].world_from_object, b.instances[i].world_from_object);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) EXPECT_EQ(a.images[i].texels8, b.images[i].texels8);
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t c = 0; c < a.cameras.size(); ++c)
    EXPECT_EQ(a.cameras[c].world_from_camera, b.cameras[c].world_from_camera);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t l = 0; l < a.lights.size(); ++l) EXPECT_EQ(a.lights[l].position, b.lights[l].position);
}

TEST(GltfSequence, EveryFrameEqualsAFreshLoadAtItsTime) {
  if (!std::filesystem::exists(shared_asset("README.md"))) GTEST_SKIP() << "no sample assets";
  struct asset_case {
    const char* file;
    bool deforms;
  };
  for (const asset_case& c : {asset_case{"CesiumMan/glTF-Binary/CesiumMan.glb", true},
                              asset_case{"BoxAnimated/glTF-Binary/BoxAnimated.glb", false},
                              asset_case{"AnimatedMorphSphere/glTF-Binary/AnimatedMorphSphere.glb", true}}) {
    SCOPED_TRACE(c.file);
    gltf_sequence sequence(shared_asset(c.file), {});
    EXPECT_TRUE(sequence.animated());
    scene previous;
    bool first = true;
    for (double time : {0.0, 0.3, 0.9, 1.7}) {
      SCOPED_TRACE(time);
      std::vector<uint32_t> posed;
      scene now = sequence.pose(time, first ? nullptr : &previous, &posed);
      EXPECT_EQ(posed.empty(), !c.deforms);
      if (!first && !previous.images.empty()) EXPECT_TRUE(previous.images[0].texels8.empty());  // moved
      gltf_load_options at;
      at.time = time;
      const scene fresh = load_gltf(shared_asset(c.file), at);
      expect_same_meshes(now, fresh);
      expect_same_placements(now, fresh);
      previous = std::move(now);
      first = false;
    }
  }
}

// Node 0 places a still triangle; node 1 another, sliding out to 1e16 (past kiln's coordinate
// limit) at t = 1. Posing t = 1 takes node 0's mesh from the last frame, then fails on node 1: the
// next pose cannot take that mesh again, and builds afresh.
TEST(GltfSequence, AFrameThatFailsHalfwayLeavesTheNextToBuildAfresh) {
  using namespace gltf_test;
  temp_folder dir;
  gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})}});
  const int sliding = b.add_node({{"mesh", b.add_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {0, 1, 2})}});
  testing::animate(b, sliding, "translation", {0, 0, 0}, {1e16f, 0, 0});
  const std::string path = b.write(dir.file("slides_away.gltf"));
  gltf_sequence sequence(path, {});
  scene previous = sequence.pose(0.0);
  const std::string message = error_of([&] { sequence.pose(1.0, &previous); });
  EXPECT_NE(message.find("/nodes/1"), std::string::npos) << message;
  const scene now = sequence.pose(0.0, &previous);
  expect_same_meshes(now, load_gltf(path));
  ASSERT_EQ(now.meshes.size(), 2u);
  EXPECT_EQ(now.meshes[0].positions.size(), 3u);
}

TEST(GltfSequence, ALongSequenceKeepsItsMemoryBudgetFlat) {
  if (!std::filesystem::exists(shared_asset("README.md"))) GTEST_SKIP() << "no sample assets";
  memory_budget budget(uint64_t(4) << 30);
  gltf_load_options options;
  options.memory = &budget;
  gltf_sequence sequence(shared_asset("CesiumMan/glTF-Binary/CesiumMan.glb"), options);
  scene previous = sequence.pose(0.0);
  previous = sequence.pose(0.1, &previous);
  const uint64_t after_two = budget.used();
  for (int frame = 2; frame < 40; ++frame) previous = sequence.pose(frame / 24.0, &previous);
  EXPECT_EQ(budget.used(), after_two);
  EXPECT_GT(after_two, 0u);
}

}  // namespace
}  // namespace kiln
