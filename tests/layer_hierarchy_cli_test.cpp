// Render layers select by hierarchy, end to end: --only and --holdout take a node's whole subtree
// (the Cornell box's `objects` group, a truck body and the wheels below it), by name, path or glob,
// and refuse an exact name that two separate nodes share, naming their paths.
#include <gtest/gtest.h>

#include "support/float_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::run_kiln;
using testing::scratch_folder;

const std::string cornell = KILN_SOURCE_DIR "/scenes/cornell_box.gltf";

testing::float_exr render(const std::string& scene, const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> args = {"render",   scene, "-o",    out, "--width", "40",
                                   "--height", "30",  "--spp", "1", "-q",      "--float"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return testing::read_float_exr(out);
}

size_t covered(const testing::float_exr& image) {
  const int a = image.spec.channelindex("A");
  size_t count = 0;
  for (size_t p = 0; a >= 0 && p < image.spec.image_pixels(); ++p)
    count += image.pixels[p * size_t(image.spec.nchannels) + size_t(a)] > 0.0f;
  return count;
}

// The Cornell box's `objects` node has no mesh; its four children are the quadrics. Selecting the
// group, its path or a glob of its children is selecting the four by name.
TEST(layer_hierarchy_cli, a_group_node_selects_every_node_below_it) {
  const std::string dir = scratch_folder("layer_hierarchy_group");
  const std::string listed = "glass_column,blue_ball,yellow_ring,orange_cone";
  const auto by_name = render(cornell, dir + "/names.exr", {"--only", listed});
  for (const std::string& group :
       {"objects", "/cornell_box/objects", "cornell_box/objects", "/cornell_box/obj*"}) {
    const auto layer = render(cornell, dir + "/group.exr", {"--only", group});
    EXPECT_EQ(layer.pixels, by_name.pixels) << group;
  }
  EXPECT_GT(covered(by_name), 100u);
  EXPECT_LT(covered(by_name), 40u * 30u / 2);  // the room is held out
  const auto held = render(cornell, dir + "/held.exr", {"--holdout", "objects"});
  EXPECT_EQ(held.pixels, render(cornell, dir + "/held_names.exr", {"--holdout", listed}).pixels);
  const auto room = render(cornell, dir + "/room.exr", {"--only", "room"});
  EXPECT_EQ(room.pixels, render(cornell, dir + "/room_glob.exr", {"--only", "room/*"}).pixels);
}

// The node tree of Khronos' CesiumMilkTruck: the body's node has the truck mesh and two unnamed
// transform nodes as children, each holding a wheel mesh.
std::string write_truck(const std::string& path) {
  gltf_builder b;
  const int paint = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.8, 1}}}}});
  const int rubber = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.1, 0.1, 1}}}}});
  const int body = b.add_node(
      {{"name", "Cesium_Milk_Truck"},
       {"mesh", b.add_mesh({{-1.5f, -0.3f, 0}, {1.5f, -0.3f, 0}, {1.5f, 1.2f, 0}, {-1.5f, 1.2f, 0}},
                           {0, 1, 2, 0, 2, 3}, paint)}});
  const int wheel = b.add_mesh({{-0.4f, -0.4f, 0}, {0.4f, -0.4f, 0}, {0.4f, 0.4f, 0}, {-0.4f, 0.4f, 0}},
                               {0, 1, 2, 0, 2, 3}, rubber);
  for (double x : {-1.0, 1.0}) {
    const int axle = b.add_node({{"translation", {x, -0.5, 0.2}}});
    b.add_child(body, axle);
    b.add_child(axle, b.add_node({{"name", "Wheels"}, {"mesh", wheel}}));
  }
  b.add_lamp_and_camera({0, 2, 4}, 20.0, {0, 0, 5}, 0.8);
  return b.write(path);
}

TEST(layer_hierarchy_cli, a_body_brings_its_child_wheels) {
  const std::string dir = scratch_folder("layer_hierarchy_truck");
  const std::string truck = write_truck(dir + "/truck.gltf");
  const auto full = render(truck, dir + "/full.exr", {});
  const auto body = render(truck, dir + "/body.exr", {"--only", "Cesium_Milk_Truck"});
  EXPECT_EQ(body.pixels, full.pixels);  // the wheels two levels down are in the layer
  const auto wheels = render(truck, dir + "/wheels.exr", {"--only", "Wheel*"});  // a glob takes both
  EXPECT_NE(wheels.pixels, full.pixels);
  EXPECT_GT(covered(wheels), 20u);
  EXPECT_EQ(covered(render(truck, dir + "/none.exr", {"--holdout", "Cesium_Milk_Truck"})), 0u);
  const auto one = render(truck, dir + "/one.exr", {"--only", "node1/Wheels"});  // an unnamed parent
  EXPECT_GT(covered(one), 10u);
  EXPECT_LT(covered(one), covered(wheels));
}

TEST(layer_hierarchy_cli, a_name_two_separate_nodes_share_is_refused_with_their_paths) {
  const std::string dir = scratch_folder("layer_hierarchy_ambiguous");
  gltf_builder b;
  const int box = b.add_mesh({{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}},
                             {0, 1, 2, 0, 2, 3});
  const int root = b.add_node({{"name", "Scene"}});
  for (const char* group : {"objects", "props"}) {
    const int parent = b.add_node({{"name", group}, {"translation", {group[0] == 'o' ? -0.6 : 0.6, 0, 0}}});
    b.add_child(root, parent);
    b.add_child(parent, b.add_node({{"name", "box"}, {"mesh", box}}));
  }
  b.add_lamp_and_camera({0, 1, 3}, 10.0, {0, 0, 4}, 0.8);
  const std::string scene = b.write(dir + "/two_boxes.gltf");
  const auto refused = run_kiln({"render", scene, "-o", dir + "/x.exr", "--only", "box"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.stderr_text.find("two_boxes.gltf: --only: 'box' names 2 nodes ('/Scene/objects/box', "
                                     "'/Scene/props/box'); give the path"),
            std::string::npos)
      << refused.stderr_text;
  const auto left = render(scene, dir + "/left.exr", {"--only", "/Scene/objects/box"});
  const auto right = render(scene, dir + "/right.exr", {"--only", "props/box"});
  EXPECT_GT(covered(left), 20u);
  EXPECT_GT(covered(right), 20u);
  EXPECT_NE(left.pixels, right.pixels);
  EXPECT_EQ(render(scene, dir + "/both.exr", {"--only", "*/box"}).pixels,
            render(scene, dir + "/all.exr", {"--only", "Scene"}).pixels);
  const auto typo = run_kiln({"render", scene, "-o", dir + "/x.exr", "--holdout", "prop"});
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.stderr_text.find("no node with geometry matches 'prop'; did you mean 'props'?"),
            std::string::npos)
      << typo.stderr_text;
}

}  // namespace
}  // namespace kiln
