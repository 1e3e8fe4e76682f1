// KILN_quadric loading: shared definitions, parameters and defaults, materials, a node with both a
// mesh and a quadric, mirrored placements, and no "unsupported extension" warning.
#include <gtest/gtest.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

TEST(GltfQuadrics, SharedDefinitionsBecomeInstancesWithMaterials) {
  temp_folder dir;
  gltf_builder b = single_triangle();  // node 0 places the triangle mesh
  b.doc["extensionsUsed"] = {"KILN_quadric"};
  b.doc["extensionsRequired"] = {"KILN_quadric"};
  b.doc["materials"] = json::array({json{{"name", "a"}}, json{{"name", "b"}}});
  b.doc["extensions"]["KILN_quadric"]["primitives"] =
      json::array({json{{"kind", "sphere"}, {"radius", 2.0}},
                   json{{"kind", "cylinder"}, {"radius", 0.5}, {"zmax", 3.0}, {"caps", true}},
                   json{{"kind", "general"},
                        {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1}},
                        {"box_min", {-1, -1, -1}},
                        {"box_max", {1, 1, 1}}},
                   json{{"kind", "torus"}, {"major_radius", 1.0}, {"minor_radius", 0.2}}});
  b.doc["nodes"][0]["extensions"]["KILN_quadric"] = {{"primitive", 3}, {"material", 1}};  // mesh + torus
  const int n1 =
      b.add_node({{"translation", {5, 0, 0}}, {"extensions", {{"KILN_quadric", {{"primitive", 0}}}}}});
  const int n2 = b.add_node(
      {{"scale", {-1, 2, 1}}, {"extensions", {{"KILN_quadric", {{"primitive", 0}, {"material", 0}}}}}});
  const int n3 = b.add_node({{"extensions", {{"KILN_quadric", {{"primitive", 1}}}}}});
  const int n4 = b.add_node({{"extensions", {{"KILN_quadric", {{"primitive", 2}}}}}});
  b.set_scene({0, n1, n2, n3, n4});
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));

  EXPECT_TRUE(s.stats.warnings.empty()) << s.stats.warnings.front();
  ASSERT_EQ(s.quadrics.size(), 4u);
  ASSERT_EQ(s.instances.size(), 6u);  // triangle, torus, sphere ×2, cylinder, general
  EXPECT_EQ(s.instances[0].kind, shape_kind::mesh);
  EXPECT_EQ(s.instances[1].kind, shape_kind::quadric);
  EXPECT_EQ(s.instances[1].shape, 3u);
  EXPECT_EQ(s.instances[2].shape, 0u);
  EXPECT_EQ(s.instances[3].shape, 0u);  // the same definition, a second instance
  EXPECT_EQ(s.instances[2].world_from_object[3], dvec4(5, 0, 0, 1));
  EXPECT_LT(glm::determinant(dmat3(s.instances[3].world_from_object)), 0.0);
  EXPECT_EQ(s.materials[s.instances[1].material].name, "b");
  EXPECT_EQ(s.materials[s.instances[3].material].name, "a");
  EXPECT_EQ(s.instances[2].material, s.instances[4].material);  // both default

  const quadric& cylinder = s.quadrics[1];
  EXPECT_EQ(cylinder.kind, quadric_kind::cylinder);
  EXPECT_EQ(cylinder.zmin, -1.0);  // default
  EXPECT_EQ(cylinder.zmax, 3.0);
  EXPECT_TRUE(cylinder.caps);
  EXPECT_EQ(cylinder.bounds.upper, dvec3(0.5, 0.5, 3.0));
  const quadric& general = s.quadrics[2];  // the unit sphere as a matrix
  EXPECT_EQ(general.coefficients[0], 1.0);
  EXPECT_EQ(general.coefficients[9], -1.0);
  EXPECT_EQ(s.quadrics[3].major_radius, 1.0);
  EXPECT_EQ(s.quadrics[3].radius, 0.2);
  // World bounds include the quadrics: the sphere at x = 5 reaches x = 7.
  EXPECT_DOUBLE_EQ(world_bounds(s).upper.x, 7.0);
}

TEST(GltfQuadrics, MalformedExtensionObjects) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["extensions"]["KILN_quadric"] = {{"primitives", 3}};
  EXPECT_NE(error_of([&] { load_gltf(b.write(dir.file("scene.gltf"))); }).find("/extensions/KILN_quadric"),
            std::string::npos);
  b.doc["extensions"]["KILN_quadric"] = {
      {"primitives", json::array({json{{"kind", "sphere"}, {"radius", 1}}})}};
  b.doc["nodes"][0]["extensions"]["KILN_quadric"] = {{"primitive", "zero"}};
  EXPECT_NE(
      error_of([&] { load_gltf(b.write(dir.file("scene.gltf"))); }).find("/nodes/0/extensions/KILN_quadric"),
      std::string::npos);
  b.doc["nodes"][0]["extensions"]["KILN_quadric"] = {{"primitive", 0}};
  b.doc["extensions"]["KILN_quadric"]["primitives"][0]["radius"] = "big";
  EXPECT_NE(error_of([&] { load_gltf(b.write(dir.file("scene.gltf"))); }).find("must be a finite number"),
            std::string::npos);
}

}  // namespace
}  // namespace kiln
