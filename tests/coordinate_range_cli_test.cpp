// Coordinates beyond Embree's range (issue 20 item 1): Embree 3.13 asserts on a ray with an origin
// or direction component past 1.844e18, in world space or in an instance's object space, and this
// build aborts (exit 134). kiln refuses such scenes before building any accelerator: exit 2, one
// line naming the file and the JSON pointer (or the option), for every backend alike.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using nlohmann::json;

// A unit quad facing +Z at the origin, placed by node 0 with `node`'s fields.
testing::gltf_builder quad_scene(const json& node, float position_scale = 1.0f) {
  testing::gltf_builder b;
  const float s = position_scale;
  b.add_mesh({{-s, -s, 0}, {s, -s, 0}, {s, s, 0}, {-s, s, 0}}, {0, 1, 2, 0, 2, 3});
  json n = {{"name", "quad"}, {"mesh", 0}};
  n.update(node, true);
  b.add_node(n);
  return b;
}

// A unit sphere quadric (or the given definition) placed by node 0 with `node`'s fields.
testing::gltf_builder quadric_scene(const json& node,
                                    const json& definition = {{"kind", "sphere"}, {"radius", 1.0}}) {
  testing::gltf_builder b;
  b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});  // the builder needs a non-empty buffer
  b.doc["extensionsUsed"] = {"KILN_quadric"};
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {definition};
  json n = {{"name", "ball"}, {"extensions", {{"KILN_quadric", {{"primitive", 0}}}}}};
  n.update(node, true);
  b.add_node(n);
  return b;
}

testing::command_result render(testing::gltf_builder& b, const std::string& name, const std::string& accel,
                               const std::vector<std::string>& extra = {}) {
  const std::string dir = testing::scratch_folder("range_" + name + "_" + accel);
  const std::string file = dir + "/" + name + ".gltf";
  b.write(file);
  std::vector<std::string> args = {"render", file,       "-o", dir + "/out.exr", "--width",
                                   "8",      "--height", "8",  "--accel",        accel};
  args.insert(args.end(), extra.begin(), extra.end());
  testing::command_result result = testing::run_kiln(args);
  EXPECT_EQ(std::filesystem::exists(dir + "/out.exr"), result.exit_code == 0) << name;
  return result;
}

// Exit 2 with one line holding the file name (when `in_file`) and every expected piece, on both
// the Embree backend and the grid.
void expect_refused(testing::gltf_builder b, const std::string& name,
                    const std::vector<std::string>& expected, const std::vector<std::string>& extra = {},
                    bool in_file = true) {
  for (const char* accel : {"embree", "grid"}) {
    const testing::command_result result = render(b, name, accel, extra);
    EXPECT_EQ(result.exit_code, 2) << name << " " << accel << ": " << result.stderr_text;
    EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
    if (in_file) {
      EXPECT_NE(result.stderr_text.find(name + ".gltf"), std::string::npos) << result.stderr_text;
    }
    for (const std::string& s : expected)
      EXPECT_NE(result.stderr_text.find(s), std::string::npos) << s << " in " << result.stderr_text;
  }
}

const std::vector<std::string> view = {"--look-from", "0,0,5", "--look-at", "0,0,0"};

TEST(coordinate_range, node_scales_out_of_range) {
  expect_refused(quad_scene({{"scale", {1e-20, 1e-20, 1e-20}}}), "scale_1e-20", {"/nodes/0/scale", "limit"});
  expect_refused(quad_scene({{"scale", {1e-45, 1e-45, 1e-45}}}), "scale_1e-45", {"/nodes/0/scale"});
  expect_refused(quad_scene({{"scale", {1e30, 1e30, 1e30}}}), "scale_1e30", {"/nodes/0/scale"});
}

TEST(coordinate_range, translation_out_of_range) {
  expect_refused(quad_scene({{"translation", {0.0, 1e30, 0.0}}}), "translation_1e30",
                 {"/nodes/0/translation"});
  // Near double's limit: refused at the node, never left to overflow the default camera's framing.
  expect_refused(quad_scene({{"translation", {1e308, 0.0, 0.0}}}), "translation_1e308",
                 {"/nodes/0/translation", "out of range"});
}

TEST(coordinate_range, positions_out_of_range) {
  expect_refused(quad_scene(json::object(), 1e37f), "positions_1e37",
                 {"/meshes/0/primitives/0/attributes/POSITION", "1e+37"});
}

TEST(coordinate_range, orthographic_window_out_of_range) {
  testing::gltf_builder b = quad_scene(json::object());
  b.add_camera({{"type", "orthographic"},
                {"orthographic", {{"xmag", 1e19}, {"ymag", 1.0}, {"znear", 0.0}, {"zfar", 100.0}}}});
  b.add_node({{"camera", 0}, {"translation", {0.0, 0.0, 5.0}}});
  expect_refused(b, "xmag_1e19", {"/cameras/0/orthographic/xmag"});
}

TEST(coordinate_range, camera_position_out_of_range) {
  expect_refused(quad_scene(json::object()), "look_from_1e19", {"--look-from", "1e+19"},
                 {"--look-from", "0,0,1e19", "--look-at", "0,0,0"}, false);
  testing::gltf_builder b = quad_scene(json::object());
  b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  b.add_node({{"camera", 0}, {"translation", {0.0, 0.0, 1e19}}});
  expect_refused(b, "camera_node_1e19", {"/nodes/1/translation", "camera"});
}

TEST(coordinate_range, quadrics_out_of_range) {
  expect_refused(quadric_scene({{"scale", {1e-20, 1e-20, 1e-20}}}), "quadric_scale_1e-20", {"/nodes/0/scale"},
                 view);
  expect_refused(quadric_scene(json::object(), {{"kind", "sphere"}, {"radius", 1e18}}), "sphere_radius_1e18",
                 {"/extensions/KILN_quadric/primitives/0", "1e+18"}, view);
}

TEST(coordinate_range, object_space_reach_of_the_camera) {
  // Each transform alone is fine, but a camera 1e14 away carried through the inverse of a 1e-2
  // scale lands at 1e16 in object space.
  expect_refused(quad_scene({{"scale", {1e-2, 1e-2, 1e-2}}}), "object_space_reach",
                 {"/nodes/0 'quad'", "object space"}, {"--look-from", "0,0,1e14", "--look-at", "0,0,0"});
}

TEST(coordinate_range, just_inside_the_limit_still_renders) {
  for (const char* accel : {"embree", "grid"}) {
    // A quad 1e12 wide seen from 3e12, and a quad scaled 1e-12 seen from 10 (object space 1e13).
    testing::gltf_builder big = quad_scene({{"scale", {1e12, 1e12, 1e12}}});
    const testing::command_result a =
        render(big, "inside_big", accel, {"--look-from", "0,0,3e12", "--look-at", "0,0,0"});
    EXPECT_EQ(a.exit_code, 0) << accel << ": " << a.stderr_text;
    testing::gltf_builder tiny = quad_scene({{"scale", {1e-12, 1e-12, 1e-12}}});
    const testing::command_result b =
        render(tiny, "inside_tiny", accel, {"--look-from", "0,0,10", "--look-at", "0,0,0"});
    EXPECT_EQ(b.exit_code, 0) << accel << ": " << b.stderr_text;
  }
}

}  // namespace
}  // namespace kiln
