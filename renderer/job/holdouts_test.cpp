// Render layers select by hierarchy: a node selects its subtree (a parent without geometry, a body
// and its child wheels), names, paths and globs of either work, an exact name shared by two
// separate subtrees is refused with their paths, and a typo gets "did you mean".
#include "job/holdouts.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace kiln {
namespace {

// Nodes:  0 scene_root ─┬─ 1 room ─┬─ 3 floor (mesh)
//                       │          └─ 4 box (mesh)
//                       └─ 2 objects ─┬─ 5 box (mesh)
//                                     └─ 6 truck (mesh) ── 7 (unnamed, no mesh) ── 8 wheel (mesh)
//         9 camera (a root, no mesh)
scene make_world() {
  scene world;
  world.source = "layers.gltf";
  world.node_names = {"scene_root", "room", "objects", "floor", "box", "box", "truck", "", "wheel", "camera"};
  world.node_parents = {-1, 0, 0, 1, 1, 2, 2, 6, 7, -1};
  for (uint32_t node : {3u, 4u, 5u, 6u, 8u}) {
    instance inst;
    inst.node = node;
    world.instances.push_back(inst);
  }
  return world;
}

// Holds out as a flat layer does: the instances outside it become mattes.
void hold_out(scene& world, const std::string& holdout, const std::string& only) {
  apply_holdouts(world, holdout, only, holdout_kind::matte);
}

// The nodes of the instances left unheld, in instance order.
std::vector<uint32_t> kept(const std::string& holdout, const std::string& only) {
  scene world = make_world();
  hold_out(world, holdout, only);
  std::vector<uint32_t> nodes;
  for (const instance& inst : world.instances)
    if (inst.holdout == holdout_kind::none)
      nodes.push_back(inst.node);
    else
      EXPECT_EQ(inst.holdout, holdout_kind::matte);
  return nodes;
}

std::string refusal(const std::string& holdout, const std::string& only) {
  scene world = make_world();
  try {
    hold_out(world, holdout, only);
  } catch (const error& e) {
    return e.what();
  }
  return "";
}

using nodes = std::vector<uint32_t>;

TEST(holdouts, a_parent_without_geometry_selects_its_subtree) {
  EXPECT_EQ(kept("", "objects"), (nodes{5, 6, 8}));
  EXPECT_EQ(kept("", "room"), (nodes{3, 4}));
  EXPECT_EQ(kept("objects", ""), (nodes{3, 4}));
  EXPECT_EQ(kept("", "scene_root"), (nodes{3, 4, 5, 6, 8}));
}

TEST(holdouts, a_node_with_a_mesh_brings_its_children) {
  EXPECT_EQ(kept("", "truck"), (nodes{6, 8}));  // the body and, two levels down, its wheel
  EXPECT_EQ(kept("truck", ""), (nodes{3, 4, 5}));
  EXPECT_EQ(kept("", "node7"), (nodes{8}));  // an unnamed node by its index name
  EXPECT_EQ(kept("", "wheel"), (nodes{8}));
}

TEST(holdouts, globs_and_paths_select_nodes_and_their_subtrees) {
  EXPECT_EQ(kept("", "fl*,tr?ck"), (nodes{3, 6, 8}));
  EXPECT_EQ(kept("", "/scene_root/objects/box"), (nodes{5}));
  EXPECT_EQ(kept("", "room/box"), (nodes{4}));              // a tail of the path
  EXPECT_EQ(kept("", "/scene_root/*/box"), (nodes{4, 5}));  // a glob matches both: wanted
  EXPECT_EQ(kept("", "/scene_root/objects/*"), (nodes{5, 6, 8}));
  EXPECT_EQ(kept("", "b[o]x"), (nodes{4, 5}));
  EXPECT_EQ(kept("", "/scene_root"), (nodes{3, 4, 5, 6, 8}));
  EXPECT_EQ(kept("", "truck,wheel"), (nodes{6, 8}));  // a node and its descendant: no conflict
}

TEST(holdouts, an_exact_name_of_two_separate_nodes_is_refused_with_their_paths) {
  const std::string message = refusal("", "box");
  EXPECT_NE(message.find("layers.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("--only"), std::string::npos) << message;
  EXPECT_NE(message.find("'box' names 2 nodes ('/scene_root/room/box', '/scene_root/objects/box')"),
            std::string::npos)
      << message;
  EXPECT_NE(refusal("box", "").find("--holdout"), std::string::npos);
}

TEST(holdouts, a_pattern_that_selects_no_geometry_is_refused) {
  const std::string typo = refusal("", "objcts");
  EXPECT_NE(typo.find("no node with geometry matches 'objcts'; did you mean 'objects'?"), std::string::npos)
      << typo;
  EXPECT_NE(typo.find("'scene_root'"), std::string::npos) << typo;  // the names are listed
  const std::string camera = refusal("camera", "");
  EXPECT_NE(camera.find("no node with geometry matches 'camera'"), std::string::npos) << camera;
  EXPECT_EQ(camera.find("did you mean"), std::string::npos) << camera;  // 'camera' itself: no geometry
  const std::string path = refusal("", "/objects/box");                 // not from the root
  EXPECT_NE(path.find("did you mean '/scene_root/objects/box'"), std::string::npos) << path;
  EXPECT_NE(refusal("", "zz*").find("no node with geometry matches 'zz*' (nodes: "), std::string::npos);
}

}  // namespace
}  // namespace kiln
