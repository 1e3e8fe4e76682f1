// Posed meshes are shared by pose, not made per node: nodes that skin one mesh with one skin, or
// morph it with equal weights, place one posed mesh, equal to what a file that gives each node a
// mesh of its own poses; nodes whose poses differ keep their own copies, charged to the memory
// budget before they are built; and a sequence poses again only what an animation deforms.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"
#include "support/animated_gltf.h"
#include "support/deforming_strip.h"

namespace kiln {
namespace {

using namespace gltf_test;
using testing::add_strip_nodes;
using testing::bend_strip;
using testing::deforming_strip;
using testing::unshared_poses;

// Each instance's shape is the reference's to the last bit, and so is its placement.
void expect_same_instances(const scene& s, const scene& reference) {
  ASSERT_EQ(s.instances.size(), reference.instances.size());
  for (size_t i = 0; i < s.instances.size(); ++i) {
    SCOPED_TRACE(i);
    const mesh& m = s.meshes.at(s.instances[i].shape);
    const mesh& r = reference.meshes.at(reference.instances[i].shape);
    EXPECT_EQ(m.positions, r.positions);
    EXPECT_EQ(m.normals, r.normals);
    EXPECT_EQ(m.indices, r.indices);
    EXPECT_EQ(s.instances[i].world_from_object, reference.instances[i].world_from_object);
  }
}

TEST(GltfSharedPose, NodesSkinningOneMeshWithOneSkinShareOnePosedMesh) {
  temp_folder dir;
  gltf_builder b = deforming_strip(8);
  add_strip_nodes(b, 0, 6);
  const scene s = load_gltf(b.write(dir.file("shared.gltf")));
  ASSERT_EQ(s.instances.size(), 6u);
  EXPECT_EQ(s.meshes.size(), 1u);  // was one posed copy per node
  const scene reference = load_gltf(unshared_poses(b).write(dir.file("unshared.gltf")));
  EXPECT_EQ(reference.meshes.size(), 6u);
  expect_same_instances(s, reference);
  // The last vertex, (2, 1, 0): morphed to (2, 1.125, 0.5), then turned 30° about joint 1 at x = 1.
  const vec3 last = s.meshes[0].positions.back();
  EXPECT_NEAR(last.x, 1.0 + 0.866025 - 0.5 * 1.125, 1e-5);
  EXPECT_NEAR(last.y, 0.5 + 0.866025 * 1.125, 1e-5);
  EXPECT_NEAR(last.z, 0.5, 1e-6);
}

TEST(GltfSharedPose, MorphedNodesShareByWeightsAndEachPlacesItsOwnCopy) {
  temp_folder dir;
  gltf_builder b = deforming_strip(8);
  add_strip_nodes(b, 1, 3);                              // the mesh's weights (0.5, 0.25)
  add_strip_nodes(b, 1, 2, {{"weights", {0.5, 0.25}}});  // the same weights, given on the node
  add_strip_nodes(b, 1, 2, {{"weights", {1.0, 0.0}}});   // a second pose
  add_strip_nodes(b, 1, 1, {{"weights", {0.0, 0.0}}});   // the rest shape: the rigid mesh
  const scene s = load_gltf(b.write(dir.file("morphs.gltf")));
  ASSERT_EQ(s.instances.size(), 8u);
  EXPECT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.instances[0].shape, s.instances[4].shape);
  EXPECT_NE(s.instances[0].shape, s.instances[5].shape);
  EXPECT_EQ(s.instances[5].shape, s.instances[6].shape);
  EXPECT_EQ(s.instances[0].shape, s.instances[1].shape);  // one mesh, each node's own place
  EXPECT_EQ(s.instances[1].world_from_object[3].z, -3.0);
  expect_same_instances(s, load_gltf(unshared_poses(b).write(dir.file("unshared.gltf"))));
}

TEST(GltfSharedPose, PosesThatDifferAreChargedBeforeTheyAreBuilt) {
  temp_folder dir;
  gltf_builder shared = deforming_strip(2000);  // 4002 vertices, 4000 triangles
  add_strip_nodes(shared, 0, 64);
  memory_budget budget(uint64_t(12) << 20);
  gltf_load_options options;
  options.memory = &budget;
  const scene s = load_gltf(shared.write(dir.file("shared.gltf")), options);
  EXPECT_EQ(s.meshes.size(), 1u);
  // 64 skins: 64 poses of ~1.3 MB each, refused before the copies are made.
  memory_budget small(uint64_t(12) << 20);
  options.memory = &small;
  const std::string path = unshared_poses(shared).write(dir.file("unshared.gltf"));
  const std::string message = error_of([&] { load_gltf(path, options); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("posed meshes (one per distinct skin and morph pose)"), std::string::npos)
      << message;
  EXPECT_NE(message.find("over the memory budget"), std::string::npos) << message;
}

TEST(GltfSharedPose, ASequencePosesAgainOnlyWhatAnAnimationDeforms) {
  temp_folder dir;
  gltf_builder b = deforming_strip(8);
  add_strip_nodes(b, 0, 3);
  // A camera dollies in: the file is animated, yet nothing the skin depends on moves.
  const int camera =
      b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  const int dolly = b.add_node({{"camera", camera}, {"translation", {1, 0, 6}}});
  testing::animate(b, dolly, "translation", {1, 0, 6}, {1, 0, 4});
  const std::string still = b.write(dir.file("still.gltf"));
  // The same with joint 1 turning: the skin moves, so every time poses its one mesh anew.
  bend_strip(b);
  const std::string bending = b.write(dir.file("bending.gltf"));

  for (const bool bends : {false, true}) {
    SCOPED_TRACE(bends);
    const std::string path = bends ? bending : still;
    gltf_sequence sequence(path, {});
    scene previous = sequence.pose(0.0);
    ASSERT_EQ(previous.meshes.size(), 1u);
    for (const double time : {0.25, 0.5, 1.0}) {
      SCOPED_TRACE(time);
      const vec3* kept = previous.meshes[0].positions.data();
      std::vector<uint32_t> posed;
      scene now = sequence.pose(time, &previous, &posed);
      ASSERT_EQ(now.meshes.size(), 1u);
      // A still pose is the last frame's mesh, moved over; a moving one is posed again.
      EXPECT_EQ(now.meshes[0].positions.data() == kept, !bends);
      EXPECT_EQ(posed, bends ? std::vector<uint32_t>{0} : std::vector<uint32_t>{});
      gltf_load_options at;
      at.time = time;
      const scene fresh = load_gltf(path, at);
      expect_same_instances(now, fresh);
      previous = std::move(now);
    }
  }
}

// Channels whose keys all hold one value pose alike at every time: joint 1's rotation keyed at its
// rest turn, and CUBICSPLINE weights of flat tangents. CUBICSPLINE keys of one value with a tangent
// that is not zero still move between the keys.
TEST(GltfSharedPose, ChannelsWhoseKeysHoldOneValueDoNotMove) {
  temp_folder dir;
  for (const float tangent : {0.0f, 1.0f}) {
    SCOPED_TRACE(tangent);
    gltf_builder b = deforming_strip(8);
    add_strip_nodes(b, 0, 2);
    add_strip_nodes(b, 1, 2);
    testing::animate(b, 1, "rotation", {0, 0, 0.258819f, 0.965926f}, {0, 0, 0.258819f, 0.965926f});
    const int times = b.add_data(std::vector<float>{0, 1}, k_float, "SCALAR", 1);
    // Per key: in-tangents, values, out-tangents of the two targets.
    const std::vector<float> keys = {0, 0, 0.5f, 0.25f, tangent, 0, 0, 0, 0.5f, 0.25f, 0, 0};
    b.doc["animations"].push_back(
        {{"samplers",
          {{{"input", times},
            {"output", b.add_data(keys, k_float, "SCALAR", 1)},
            {"interpolation", "CUBICSPLINE"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 4}, {"path", "weights"}}}}}}});
    const std::string path = b.write(dir.file("held.gltf"));
    gltf_sequence sequence(path, {});
    scene previous = sequence.pose(0.0);
    ASSERT_EQ(previous.meshes.size(), 3u);  // the skinned pose, node 4's own, node 5's
    const uint32_t morphed = previous.instances.at(2).shape;
    std::vector<uint32_t> posed;
    const scene now = sequence.pose(0.5, &previous, &posed);
    EXPECT_EQ(posed, tangent == 0.0f ? std::vector<uint32_t>{} : std::vector<uint32_t>{morphed});
    gltf_load_options at;
    at.time = 0.5;
    expect_same_instances(now, load_gltf(path, at));
    // With the tangent the weights bulge above (0.5, 0.25) halfway: the vertices rise above z = 0.5.
    EXPECT_EQ(now.meshes.at(morphed).positions[0].z > 0.5f, tangent != 0.0f);
  }
}

}  // namespace
}  // namespace kiln
