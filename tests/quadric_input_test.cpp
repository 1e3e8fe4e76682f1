// Bad KILN_quadric input from the command line: exit code 2 and one line naming the file, the
// JSON path and the node. Never a crash, never a half-written image.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using nlohmann::json;

struct bad_case {
  const char* name;
  json definition;
  json node;                          // the placing node's extra fields
  std::vector<std::string> expected;  // substrings of the one error line
};

void check(const bad_case& c) {
  testing::gltf_builder b;
  b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});  // the builder needs a non-empty buffer
  b.doc["extensionsUsed"] = {"KILN_quadric"};
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {json{{"kind", "sphere"}, {"radius", 1.0}},
                                                       c.definition};
  b.add_node({{"name", "fine"}, {"extensions", {{"KILN_quadric", {{"primitive", 0}}}}}});
  json node = {{"name", "culprit"}, {"extensions", {{"KILN_quadric", {{"primitive", 1}}}}}};
  node.update(c.node, true);
  b.add_node(node);
  std::string dir = testing::scratch_folder(std::string("quadric_") + c.name);
  std::string file = dir + "/" + c.name + ".gltf";
  b.write(file);
  auto result = testing::run_kiln({"render", file, "-o", dir + "/out.exr", "--width", "8", "--height", "8"});
  EXPECT_EQ(result.exit_code, 2) << c.name << ": " << result.stderr_text;
  EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find(file), std::string::npos) << result.stderr_text;
  for (const std::string& s : c.expected)
    EXPECT_NE(result.stderr_text.find(s), std::string::npos) << s << " in " << result.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));
}

TEST(quadric_input, unknown_kind) {
  check(
      {"unknown_kind",
       {{"kind", "klein_bottle"}},
       json::object(),
       {"/extensions/KILN_quadric/primitives/1/kind", "unknown kind 'klein_bottle'", "/nodes/1 'culprit'"}});
}

TEST(quadric_input, negative_radius) {
  check({"negative_radius",
         {{"kind", "cylinder"}, {"radius", -0.5}},
         json::object(),
         {"/extensions/KILN_quadric/primitives/1/radius", "greater than 0", "/nodes/1 'culprit'"}});
}

TEST(quadric_input, missing_parameter) {
  check(
      {"missing_parameter",
       {{"kind", "torus"}, {"major_radius", 1.0}},
       json::object(),
       {"/extensions/KILN_quadric/primitives/1", "missing parameter 'minor_radius'", "/nodes/1 'culprit'"}});
  check({"missing_box",
         {{"kind", "general"}, {"coefficients", {1, 1, 1, 0, 0, 0, 0, 0, 0, -1}}},
         json::object(),
         {"missing parameter 'box_min'", "/nodes/1 'culprit'"}});
}

TEST(quadric_input, non_invertible_transform) {
  check({"zero_scale",
         {{"kind", "sphere"}, {"radius", 1.0}},
         {{"scale", {1.0, 0.0, 1.0}}},
         {"/nodes/1/extensions/KILN_quadric", "not invertible"}});
}

TEST(quadric_input, bad_references) {
  check({"primitive_out_of_range",
         {{"kind", "sphere"}, {"radius", 1.0}},
         {{"extensions", {{"KILN_quadric", {{"primitive", 7}}}}}},
         {"/nodes/1/extensions/KILN_quadric/primitive",
          "/extensions/KILN_quadric/primitives/7 does not exist"}});
  check({"material_out_of_range",
         {{"kind", "sphere"}, {"radius", 1.0}},
         {{"extensions", {{"KILN_quadric", {{"primitive", 1}, {"material", 3}}}}}},
         {"/nodes/1/extensions/KILN_quadric/material"}});
}

TEST(quadric_input, impossible_clipping) {
  check({"inverted_range",
         {{"kind", "cylinder"}, {"radius", 1.0}, {"zmin", 1.0}, {"zmax", -1.0}},
         json::object(),
         {"/extensions/KILN_quadric/primitives/1/zmax", "zmin must be less than zmax", "/nodes/1"}});
  check({"between_sheets",
         {{"kind", "hyperboloid_two_sheets"}, {"radius", 1.0}, {"c", 2.0}, {"zmin", -1.0}, {"zmax", 1.0}},
         json::object(),
         {"between the sheets", "/nodes/1"}});
}

}  // namespace
}  // namespace kiln
