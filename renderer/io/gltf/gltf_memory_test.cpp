// Shared geometry and the loader's memory charges: primitives on the same accessors build one
// scene mesh, and a budget too small for a file's JSON, buffers or meshes refuses it.
#include <gtest/gtest.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// One mesh whose `primitives` primitives all use the same POSITION and index accessors,
// alternating between two materials.
gltf_builder shared_primitives(int primitives) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, k_ushort, "SCALAR", 1);
  b.doc["materials"] = json::array({json{{"name", "red"}}, json{{"name", "green"}}});
  json list = json::array();
  for (int p = 0; p < primitives; ++p)
    list.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"material", p % 2}});
  b.doc["meshes"].push_back(json{{"primitives", list}});
  b.set_scene({b.add_node({{"mesh", 0}})});
  return b;
}

TEST(GltfSharedGeometry, PrimitivesOnOneAccessorMakeOneMesh) {
  temp_folder dir;
  const scene s = load_gltf(shared_primitives(100).write(dir.file("scene.gltf")));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 6u);
  ASSERT_EQ(s.instances.size(), 100u);
  for (size_t i = 0; i < s.instances.size(); ++i) {
    EXPECT_EQ(s.instances[i].shape, 0u);
    // Each instance keeps its own primitive's material.
    EXPECT_EQ(s.materials[s.instances[i].material].name, i % 2 == 0 ? "red" : "green") << i;
  }
}

TEST(GltfSharedGeometry, DifferentAttributesStayApart) {
  temp_folder dir;
  gltf_builder b = shared_primitives(1);
  const int normals = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, k_float, "VEC3", 3);
  json second = b.doc["meshes"][0]["primitives"][0];
  second["attributes"]["NORMAL"] = normals;
  b.doc["meshes"][0]["primitives"].push_back(second);
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_TRUE(s.meshes[0].normals.empty());
  EXPECT_EQ(s.meshes[1].normals.size(), 4u);
}

TEST(GltfMemoryBudget, ChargesTheSceneAndRefusesPastTheBudget) {
  temp_folder dir;
  const std::string path = shared_primitives(2).write(dir.file("scene.gltf"));
  memory_budget roomy(uint64_t(1) << 30);
  gltf_load_options options;
  options.memory = &roomy;
  load_gltf(path, options);
  // The mesh stays charged; the JSON's parse and the buffers were released with the model.
  EXPECT_GT(roomy.used(), 0u);
  EXPECT_LT(roomy.used(), 4096u);

  memory_budget tight(1000);
  options.memory = &tight;
  try {
    load_gltf(path, options);
    FAIL() << "a 1000-byte budget was accepted";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_NE(e.reason().find("over the memory budget of 1000 bytes (raise it with --max-memory)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(tight.used(), 0u);  // what loading charged is released again
}

}  // namespace
}  // namespace kiln
