// Loader tests for EXT_mesh_gpu_instancing and KHR_mesh_quantization on small files the tests
// write themselves: exact per-instance transforms, mesh sharing, quantized attribute decoding,
// and the errors bad extension data must raise.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

const std::string instancing_at = "/nodes/0/extensions/EXT_mesh_gpu_instancing/attributes";

void expect_matrix_near(const dmat4& got, const dmat4& expected, double tol) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], expected[c][r], tol) << "column " << c << " row " << r;
}

// The triangle of single_triangle() placed by node 0 with the given instancing attributes.
gltf_builder instanced_triangle(const json& attributes) {
  gltf_builder b = single_triangle();
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = attributes;
  return b;
}

TEST(GltfInstancing, ThreeInstancesShareOneMeshWithExactTransforms) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  const float h = std::sqrt(0.5f);
  const int t = b.add_data(std::vector<float>{1, 2, 3, 0, 0, 0, -4, 0, 0}, k_float, "VEC3", 3);
  const int r = b.add_data(std::vector<float>{0, 0, 0, 1, 0, 0, h, h, 1, 0, 0, 0}, k_float, "VEC4", 4);
  const int s = b.add_data(std::vector<float>{1, 1, 1, 2, 2, 2, 1, 3, 1}, k_float, "VEC3", 3);
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.doc["nodes"][0]["translation"] = {10, 0, 0};  // the node is the instances' parent
  b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
      {"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", s}};
  const scene sc = load_gltf(b.write(dir.file("scene.gltf")));

  ASSERT_EQ(sc.meshes.size(), 1u);
  ASSERT_EQ(sc.instances.size(), 3u);
  EXPECT_TRUE(sc.stats.warnings.empty());
  const dmat4 parent = glm::translate(dmat4(1.0), dvec3(10, 0, 0));
  const double half_turn = 3.14159265358979323846;
  const dmat4 expected[3] = {
      parent * glm::translate(dmat4(1.0), dvec3(1, 2, 3)),
      parent * glm::rotate(dmat4(1.0), half_turn / 2, dvec3(0, 0, 1)) * glm::scale(dmat4(1.0), dvec3(2.0)),
      parent * glm::translate(dmat4(1.0), dvec3(-4, 0, 0)) *
          glm::rotate(dmat4(1.0), half_turn, dvec3(1, 0, 0)) * glm::scale(dmat4(1.0), dvec3(1, 3, 1)),
  };
  for (size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(sc.instances[i].shape, 0u);
    EXPECT_EQ(sc.instances[i].node, 0u);
    expect_matrix_near(sc.instances[i].world_from_object, expected[i], 1e-7);
    expect_matrix_near(sc.instances[i].object_from_world * sc.instances[i].world_from_object, dmat4(1.0),
                       1e-7);
  }
  // Vertex (1, 0, 0): scaled by 2 and turned a quarter about z lands on (0, 2, 0), then the parent.
  const dvec3 p = transform_point(sc.instances[1].world_from_object, dvec3(1, 0, 0));
  EXPECT_NEAR(p.x, 10.0, 1e-7);
  EXPECT_NEAR(p.y, 2.0, 1e-7);
  // Instance 2: a half turn about x maps vertex (0, 1, 0), scaled to (0, 3, 0), to (0, -3, 0).
  const dvec3 q = transform_point(sc.instances[2].world_from_object, dvec3(0, 1, 0));
  EXPECT_NEAR(q.x, 6.0, 1e-7);
  EXPECT_NEAR(q.y, -3.0, 1e-7);
  EXPECT_NEAR(q.z, 0.0, 1e-7);
}

// A unit cube: 8 corners, 12 triangles.
int add_box_mesh(gltf_builder& b) {
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1});
  const int idx = b.add_data(std::vector<uint16_t>{0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                                   2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3},
                             k_ushort, "SCALAR", 1);
  return b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
}

TEST(GltfInstancing, HundredThousandInstancesCostTransformsNotMeshes) {
  temp_folder dir;
  gltf_builder b;
  const int mesh_index = add_box_mesh(b);
  constexpr size_t side = 100, layers = 10, count = side * side * layers;  // 100,000
  std::vector<float> translations;
  translations.reserve(count * 3);
  for (size_t z = 0; z < layers; ++z)
    for (size_t y = 0; y < side; ++y)
      for (size_t x = 0; x < side; ++x)
        translations.insert(translations.end(), {2.0f * x, 2.0f * y, 2.0f * z});
  const int t = b.add_data(translations, k_float, "VEC3", 3);
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.set_scene(
      {b.add_node({{"mesh", mesh_index},
                   {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", t}}}}}}}})});
  const std::string path = dir.file("boxes.glb");
  write_bytes(path, b.glb_bytes());
  const scene s = load_gltf(path);

  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), count);
  // The mesh data is stored once: 8 corners and 36 indices, whatever the instance count.
  EXPECT_EQ(s.meshes[0].positions.size(), 8u);
  EXPECT_EQ(s.meshes[0].indices.size(), 36u);
  for (const instance& inst : s.instances) ASSERT_EQ(inst.shape, 0u);
  const dvec3 last = transform_point(s.instances.back().world_from_object, dvec3(0.0));
  EXPECT_EQ(last, dvec3(198, 198, 18));
  const bounds3 world = world_bounds(s);
  EXPECT_EQ(world.lower, dvec3(0.0));
  EXPECT_EQ(world.upper, dvec3(199, 199, 19));
}

TEST(GltfInstancing, EachPrimitiveOfTheMeshIsPlacedPerInstance) {
  temp_folder dir;
  gltf_builder b = instanced_triangle({});
  const int pos = b.add_positions({0, 0, 0, 0, 1, 0, 0, 0, 1});
  b.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos}}}});
  const int t = b.add_data(std::vector<float>{0, 0, 0, 5, 0, 0}, k_float, "VEC3", 3);
  b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"TRANSLATION", t}};
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.meshes.size(), 2u);
  ASSERT_EQ(s.instances.size(), 4u);  // instance-major: (0, prim 0), (0, prim 1), (1, prim 0), (1, prim 1)
  EXPECT_EQ(s.instances[0].shape, 0u);
  EXPECT_EQ(s.instances[1].shape, 1u);
  EXPECT_EQ(s.instances[2].shape, 0u);
  EXPECT_EQ(s.instances[3].shape, 1u);
  EXPECT_DOUBLE_EQ(s.instances[1].world_from_object[3].x, 0.0);
  EXPECT_DOUBLE_EQ(s.instances[3].world_from_object[3].x, 5.0);
}

TEST(GltfInstancing, NormalizedShortRotationAndZeroScaleInstances) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  // A half turn about z as a normalized SHORT quaternion (0, 0, 32767, 0).
  const int r = b.add_data(std::vector<int16_t>{0, 0, 32767, 0, 0, 0, 0, 32767}, k_short, "VEC4", 4, true);
  const int s = b.add_data(std::vector<float>{1, 1, 1, 0, 0, 0}, k_float, "VEC3", 3);
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"ROTATION", r}, {"SCALE", s}};
  const scene sc = load_gltf(b.write(dir.file("scene.gltf")));
  // The second instance has zero scale: it is not placed, and one warning says so.
  ASSERT_EQ(sc.instances.size(), 1u);
  expect_matrix_near(sc.instances[0].world_from_object, glm::scale(dmat4(1.0), dvec3(-1, -1, 1)), 1e-12);
  ASSERT_EQ(sc.stats.warnings.size(), 1u);
  EXPECT_NE(sc.stats.warnings[0].find("EXT_mesh_gpu_instancing: 1 instances have a singular transform"),
            std::string::npos)
      << sc.stats.warnings[0];
}

TEST(GltfInstancing, QuantizedTranslationNeedsKhrMeshQuantization) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  const int t = b.add_data(std::vector<int16_t>{3, -2, 7}, k_short, "VEC3", 3);
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"TRANSLATION", t}};
  std::string message = error_of([&] { load_gltf(b.write(dir.file("scene.gltf"))); });
  EXPECT_NE(message.find(instancing_at + "/TRANSLATION: TRANSLATION must be VEC3 FLOAT (got VEC3 SHORT)"),
            std::string::npos)
      << message;
  b.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
  const scene s = load_gltf(b.write(dir.file("scene.gltf")));
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(transform_point(s.instances[0].world_from_object, dvec3(0.0)), dvec3(3, -2, 7));
}

TEST(GltfInstancing, BadAttributesNameTheJsonPath) {
  temp_folder dir;
  struct bad_case {
    const char* what;
    std::function<void(gltf_builder&)> damage;
    std::string expected;
  };
  const std::vector<bad_case> cases = {
      {"mismatched counts",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] =
             b.add_data(std::vector<float>{1, 1, 1, 1, 1, 1}, k_float, "VEC3", 3);
       },
       instancing_at + "/SCALE: SCALE has 2 instances but TRANSLATION has 3"},
      {"wrong type",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] =
             b.add_data(std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, 0}, k_float, "VEC3", 3);
       },
       instancing_at + "/ROTATION: ROTATION must be VEC4 FLOAT or normalized BYTE/SHORT (got VEC3 FLOAT)"},
      {"unnormalized integer rotation",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] =
             b.add_data(std::vector<int8_t>(12, 1), k_byte, "VEC4", 4);
       },
       instancing_at + "/ROTATION: ROTATION must be VEC4 FLOAT or normalized BYTE/SHORT (got VEC4 BYTE)"},
      {"NaN",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] =
             b.add_data(std::vector<float>{1, 1, 1, 1, std::nanf(""), 1, 1, 1, 1}, k_float, "VEC3", 3);
       },
       instancing_at + "/SCALE: instance 1 is NaN or infinite"},
      {"infinity",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] =
             b.add_data(std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, INFINITY}, k_float, "VEC3", 3);
       },
       instancing_at + "/TRANSLATION: instance 2 is NaN or infinite"},
      {"zero quaternion",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] =
             b.add_data(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1}, k_float, "VEC4", 4);
       },
       instancing_at + "/ROTATION: instance 1 has a zero-length rotation quaternion"},
      {"missing accessor",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] = 99;
       },
       instancing_at + "/SCALE: /accessors/99 does not exist"},
      {"only custom attributes",
       [](gltf_builder& b) {
         b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"_ID", 0}};
       },
       instancing_at + ": attributes name none of TRANSLATION, ROTATION and SCALE"},
  };
  for (const bad_case& c : cases) {
    SCOPED_TRACE(c.what);
    gltf_builder b = instanced_triangle({});
    b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] =
        b.add_data(std::vector<float>{0, 0, 0, 1, 0, 0, 2, 0, 0}, k_float, "VEC3", 3);
    c.damage(b);
    const std::string path = b.write(dir.file("scene.gltf"));
    const std::string message = error_of([&] { load_gltf(path); });
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

TEST(GltfInstancing, InstanceCountIsLimited) {
  temp_folder dir;
  gltf_builder b = instanced_triangle({});
  b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] =
      b.add_data(std::vector<float>(9, 0.0f), k_float, "VEC3", 3);
  const std::string path = b.write(dir.file("scene.gltf"));
  gltf_load_options options;
  options.limits.max_instances = 2;
  const std::string message = error_of([&] { load_gltf(path, options); });
  EXPECT_NE(message.find(
                instancing_at +
                "/TRANSLATION: 3 instances take the scene past the limit of 2 instances (--max-instances)"),
            std::string::npos)
      << message;
  options.limits.max_instances = 3;
  EXPECT_EQ(load_gltf(path, options).instances.size(), 3u);
}

// ---- KHR_mesh_quantization ------------------------------------------------------------------

// A quad with SHORT positions (not normalized) and normalized BYTE normals.
gltf_builder quantized_quad(bool declare) {
  gltf_builder b;
  const int pos =
      b.add_data(std::vector<int16_t>{0, 0, 0, 300, 0, 0, 300, 200, 0, 0, 200, 0}, k_short, "VEC3", 3);
  const int nrm =
      b.add_data(std::vector<int8_t>{0, 0, 127, 90, 0, 90, 0, -128, 0, 0, 0, 64}, k_byte, "VEC3", 3, true);
  const int idx = b.add_data(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, k_ubyte, "SCALAR", 1);
  const int mesh_index = b.add_mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}});
  b.set_scene({b.add_node({{"mesh", mesh_index}, {"scale", {0.01, 0.01, 0.01}}})});
  if (declare) {
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  }
  return b;
}

TEST(GltfQuantization, ShortPositionsAndByteNormalsDecodeWhenDeclared) {
  temp_folder dir;
  const scene s = load_gltf(quantized_quad(true).write(dir.file("scene.gltf")));
  ASSERT_EQ(s.meshes.size(), 1u);
  const mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[2], vec3(300, 200, 0));  // integers keep their value; the node scale dequantizes
  const bounds3 world = world_bounds(s);
  EXPECT_NEAR(world.upper.x, 3.0, 1e-12);
  EXPECT_NEAR(world.upper.y, 2.0, 1e-12);
  ASSERT_EQ(m.normals.size(), 4u);
  const vec3 expected[4] = {{0, 0, 1}, {std::sqrt(0.5f), 0, std::sqrt(0.5f)}, {0, -1, 0}, {0, 0, 1}};
  for (size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-6f);
    EXPECT_NEAR(m.normals[i].x, expected[i].x, 1e-6f);
    EXPECT_NEAR(m.normals[i].y, expected[i].y, 1e-6f);
    EXPECT_NEAR(m.normals[i].z, expected[i].z, 1e-6f);
  }
}

TEST(GltfQuantization, IntegerAttributesAreRefusedWithoutTheExtension) {
  temp_folder dir;
  const std::string path = quantized_quad(false).write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("/meshes/0/primitives/0/attributes/NORMAL: NORMAL must be VEC3 FLOAT (got VEC3 BYTE "
                         "normalized); integer formats need KHR_mesh_quantization"),
            std::string::npos)
      << message;
}

TEST(GltfQuantization, FormatRulesFollowTheExtension) {
  temp_folder dir;
  struct format_case {
    const char* attribute;
    int component;
    bool normalized;
    bool accepted;
  };
  // With the extension declared: what KHR_mesh_quantization allows, and what it still forbids.
  const format_case cases[] = {
      {"POSITION", k_ubyte, false, true},   {"POSITION", k_short, true, true},
      {"POSITION", k_uint, false, false},   {"NORMAL", k_short, true, true},
      {"NORMAL", k_short, false, false},    {"NORMAL", k_ubyte, true, false},
      {"TANGENT", k_byte, true, true},      {"TANGENT", k_ushort, true, false},
      {"TEXCOORD_0", k_byte, false, true},  {"TEXCOORD_0", k_ushort, false, true},
      {"TEXCOORD_0", k_uint, false, false},
  };
  for (const format_case& c : cases) {
    SCOPED_TRACE(std::string(c.attribute) + " " + std::to_string(c.component) +
                 (c.normalized ? " normalized" : ""));
    gltf_builder b = single_triangle();
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    const std::string name = c.attribute;
    const std::string type = name == "TANGENT" ? "VEC4" : name == "TEXCOORD_0" ? "VEC2" : "VEC3";
    const size_t components = type == "VEC4" ? 4 : type == "VEC2" ? 2 : 3;
    const size_t size = c.component == k_uint                                 ? 4
                        : (c.component == k_short || c.component == k_ushort) ? 2
                                                                              : 1;
    const size_t element = size * components;
    const size_t stride = (element + 3) / 4 * 4;  // each vertex starts on a 4-byte boundary
    // Vertex v has a 1 in component (v + 2) % 3 and 0 elsewhere: (0,0,1), (1,0,0), (0,1,0), a
    // proper triangle when it is POSITION.
    std::vector<uint8_t> data(stride * 3, 0);
    for (size_t v = 0; v < 3; ++v) data[v * stride + ((v + 2) % 3) * size] = 1;
    const int strided_view = b.add_view(data.data(), data.size(), static_cast<int>(stride));
    const int acc = b.add_accessor(strided_view, c.component, 3, type, 0, c.normalized);
    b.doc["meshes"][0]["primitives"][0]["attributes"][name] = acc;
    const std::string path = b.write(dir.file("scene.gltf"));
    if (c.accepted) {
      EXPECT_NO_THROW(load_gltf(path));
    } else {
      const std::string message = error_of([&] { load_gltf(path); });
      EXPECT_NE(message.find("/attributes/" + name + ": " + name + " must be"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace kiln
