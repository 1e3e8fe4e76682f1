// Posing on small files the tests write themselves, against closed forms: node animation by
// LINEAR, STEP and CUBICSPLINE samplers (translation, rotation with shortest-path slerp, camera
// nodes), morph targets with default, node and animated weights (sparse deltas included), a
// skinned two-bone arm, the choice of animation and every refusal of bad animation or skin data.
#include <gtest/gtest.h>

#include <cmath>

#include "io/gltf/gltf_animation.h"
#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

constexpr double tol = 1e-6;

// A builder holding one triangle mesh placed by node 0; extra JSON goes on the node.
gltf_builder triangle_node(const json& node_extra = json::object()) {
  gltf_builder b;
  const int mesh = b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  json node = {{"mesh", mesh}};
  for (auto& [key, value] : node_extra.items()) node[key] = value;
  b.add_node(node);
  return b;
}

// Adds animation {sampler: times -> values, channel on node.path}; returns the animation index.
int add_animation(gltf_builder& b, int node, const std::string& path, const std::vector<float>& times,
                  const std::vector<float>& values, const std::string& type, size_t components,
                  const std::string& interpolation = "LINEAR", const std::string& name = "") {
  const int input = b.add_data(times, k_float, "SCALAR", 1);
  const int output = b.add_data(values, k_float, type, components);
  json anim = {{"samplers", {{{"input", input}, {"output", output}, {"interpolation", interpolation}}}},
               {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}}}};
  if (!name.empty()) anim["name"] = name;
  b.doc["animations"].push_back(anim);
  return static_cast<int>(b.doc["animations"].size() - 1);
}

scene load_at(const gltf_builder& b, const temp_folder& dir, double time, const std::string& animation = "") {
  gltf_load_options options;
  options.time = time;
  options.animation = animation;
  return load_gltf(b.write(dir.file("posed.gltf")), options);
}

dvec3 translation_of(const scene& s, size_t instance = 0) {
  return dvec3(s.instances.at(instance).world_from_object[3]);
}

TEST(GltfAnimation, LinearTranslationInterpolatesAndHoldsTheEnds) {
  temp_folder dir;
  gltf_builder b = triangle_node();
  add_animation(b, 0, "translation", {1, 3}, {0, 0, 0, 4, 2, 0}, "VEC3", 3);
  // x = 2 (t - 1), y = t - 1 between the keys; before and after, the end values.
  for (const auto& [t, x, y] : std::vector<std::tuple<double, double, double>>{{1.5, 1.0, 0.5},
                                                                               {2.0, 2.0, 1.0},
                                                                               {2.75, 3.5, 1.75},
                                                                               {0.0, 0.0, 0.0},
                                                                               {-7.0, 0.0, 0.0},
                                                                               {3.0, 4.0, 2.0},
                                                                               {99.0, 4.0, 2.0}}) {
    SCOPED_TRACE(t);
    const dvec3 p = translation_of(load_at(b, dir, t));
    EXPECT_NEAR(p.x, x, tol);
    EXPECT_NEAR(p.y, y, tol);
    EXPECT_NEAR(p.z, 0.0, tol);
  }
}

TEST(GltfAnimation, StepHoldsEachKeyUntilTheNext) {
  temp_folder dir;
  gltf_builder b = triangle_node();
  add_animation(b, 0, "translation", {0, 1, 2}, {0, 0, 0, 1, 0, 0, 5, 0, 0}, "VEC3", 3, "STEP");
  for (const auto& [t, x] : std::vector<std::pair<double, double>>{
           {0.0, 0.0}, {0.99, 0.0}, {1.0, 1.0}, {1.5, 1.0}, {1.999, 1.0}, {2.0, 5.0}, {3.0, 5.0}}) {
    SCOPED_TRACE(t);
    EXPECT_NEAR(translation_of(load_at(b, dir, t)).x, x, tol);
  }
}

TEST(GltfAnimation, CubicSplineIsTheHermiteCurveWithTangentsScaledByTheInterval) {
  temp_folder dir;
  gltf_builder b = triangle_node();
  // Keys at t = 1 and 3 (interval 2): x goes 0 -> 2 with out-tangent 1 at the first key and
  // in-tangent 3 at the second; each key stores in-tangent, value, out-tangent.
  add_animation(b, 0, "translation", {1, 3},
                {/*key 0*/ 9, 9, 9, 0, 0, 0, 1, 0, 0, /*key 1*/ 3, 0, 0, 2, 0, 0, 9, 9, 9}, "VEC3", 3,
                "CUBICSPLINE");
  // u = (t - 1) / 2; x(u) = h10(u)·2·1 + h01(u)·2 + h11(u)·2·3 with h10 = u³−2u²+u,
  // h01 = −2u³+3u², h11 = u³−u². At u = 1/4: 0.28125 + 0.3125 − 0.28125 = 0.3125; at u = 1/2:
  // 0.25 + 1 − 0.75 = 0.5; at u = 3/4: 0.09375 + 1.6875 − 0.84375 = 0.9375.
  for (const auto& [t, x] : std::vector<std::pair<double, double>>{
           {1.5, 0.3125}, {2.0, 0.5}, {2.5, 0.9375}, {1.0, 0.0}, {3.0, 2.0}, {0.0, 0.0}, {4.0, 2.0}}) {
    SCOPED_TRACE(t);
    const dvec3 p = translation_of(load_at(b, dir, t));
    EXPECT_NEAR(p.x, x, tol);
    EXPECT_NEAR(p.y, 0.0, tol);  // tangents' other components are 0; the 9s are never read
  }
}

TEST(GltfAnimation, LinearRotationIsTheShortestPathSlerp) {
  temp_folder dir;
  const float h = std::sqrt(0.5f);
  for (const float sign : {1.0f, -1.0f}) {
    SCOPED_TRACE(sign);
    gltf_builder b = triangle_node();
    // Identity to 90° about +Z; the second key is stored negated (the same rotation) and at twice
    // unit length: the slerp must still take the short way and normalize.
    add_animation(b, 0, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, 2 * sign * h, 2 * sign * h}, "VEC4", 4);
    for (const double t : {0.25, 0.5, 0.9}) {
      SCOPED_TRACE(t);
      const dmat4 m = load_at(b, dir, t).instances.at(0).world_from_object;
      const double angle = t * pi / 2;  // slerp turns at constant speed
      EXPECT_NEAR(m[0][0], std::cos(angle), tol);
      EXPECT_NEAR(m[0][1], std::sin(angle), tol);
      EXPECT_NEAR(m[1][0], -std::sin(angle), tol);
      EXPECT_NEAR(m[2][2], 1.0, tol);
    }
  }
}

// A quaternion is normalised by scaling it by its largest component first: (1e200, 0, 0, 0) has
// an infinite squared length and became the identity; (1e-170, 0, 0, 0) has a squared length
// that underflows to zero and was refused as zero. Both are a half turn about x.
TEST(GltfAnimation, HugeAndTinyRotationQuaternionsAreTheRotationTheyName) {
  temp_folder dir;
  for (const double x : {1e200, 1e-170, 2.0}) {
    SCOPED_TRACE(x);
    const dmat4 m =
        load_at(triangle_node({{"rotation", {x, 0, 0, 0}}}), dir, 0.0).instances.at(0).world_from_object;
    EXPECT_EQ(m[0][0], 1.0);
    EXPECT_EQ(m[1][1], -1.0);
    EXPECT_EQ(m[2][2], -1.0);
  }
}

// CUBICSPLINE's curve from q to -q with flat tangents passes through zero halfway: no rotation.
// It was normalised to NaN and reported as "/nodes/0: world transform overflows to infinity".
TEST(GltfAnimation, ACubicSplineRotationThroughZeroIsRefusedAtItsSampler) {
  temp_folder dir;
  gltf_builder b = triangle_node();
  add_animation(b, 0, "rotation", {0, 1}, {/*key 0*/ 0, 0, 0, 0, 0, 0, 0, 1,  0, 0, 0, 0,
                                           /*key 1*/ 0, 0, 0, 0, 0, 0, 0, -1, 0, 0, 0, 0},
                "VEC4", 4, "CUBICSPLINE");
  EXPECT_NEAR(load_at(b, dir, 0.25).instances.at(0).world_from_object[0][0], 1.0, tol);
  EXPECT_EQ(error_of([&] { load_at(b, dir, 0.5); }),
            dir.file("posed.gltf") +
                ": /animations/0/samplers/0/output: at time 0.5 the keyframes interpolate to a zero-length "
                "rotation quaternion");
}

TEST(GltfAnimation, ChannelsReplaceOnlyWhatTheyDriveAndCamerasMoveToo) {
  temp_folder dir;
  gltf_builder b = triangle_node({{"scale", {2, 2, 2}}, {"translation", {0, 0, 7}}});
  b.add_node(
      {{"camera", b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}})},
       {"translation", {0, 0, 10}}});
  add_animation(b, 0, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, 1, 0}, "VEC4", 4, "STEP");
  add_animation(b, 1, "translation", {0, 2}, {0, 0, 10, 4, 0, 10}, "VEC3", 3);
  const scene s = load_at(b, dir, 1.0);
  const dmat4 m = s.instances.at(0).world_from_object;
  // At t = 1 STEP has reached key 1, 180° about Z; the node's translation and scale stay.
  EXPECT_NEAR(m[3][2], 7.0, tol);
  EXPECT_NEAR(m[0][0], -2.0, tol);
  EXPECT_NEAR(m[1][1], -2.0, tol);
  EXPECT_NEAR(m[2][2], 2.0, tol);
  ASSERT_EQ(s.cameras.size(), 1u);  // the camera slides halfway to x = 4
  EXPECT_NEAR(s.cameras[0].world_from_camera[3][0], 2.0, tol);
  EXPECT_NEAR(s.cameras[0].world_from_camera[3][2], 10.0, tol);
}

TEST(GltfAnimation, AllAnimationsPlayByDefaultAndOneCanBeChosen) {
  temp_folder dir;
  gltf_builder b = triangle_node();
  b.add_node({{"mesh", 0}});
  add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", 3, "LINEAR", "slide");
  add_animation(b, 1, "translation", {0, 1}, {0, 0, 0, 0, 3, 0}, "VEC3", 3, "LINEAR", "lift");
  add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 0, 0, -5}, "VEC3", 3, "LINEAR", "sink");
  {
    const scene s = load_at(b, dir, 1.0);  // all: node 0 by the first (slide), node 1 by lift
    EXPECT_NEAR(translation_of(s, 0).x, 1.0, tol);
    EXPECT_NEAR(translation_of(s, 0).z, 0.0, tol);
    EXPECT_NEAR(translation_of(s, 1).y, 3.0, tol);
    bool warned = false;
    for (const std::string& w : s.stats.warnings)
      warned |= w.find("both drive translation of /nodes/0") != std::string::npos;
    EXPECT_TRUE(warned);
  }
  {
    const scene s = load_at(b, dir, 1.0, "sink");
    EXPECT_NEAR(translation_of(s, 0).z, -5.0, tol);
    EXPECT_NEAR(translation_of(s, 1).y, 0.0, tol);  // lift does not play
  }
  EXPECT_NEAR(translation_of(load_at(b, dir, 1.0, "1"), 1).y, 3.0, tol);
  const std::string message = error_of([&] { load_at(b, dir, 1.0, "walk"); });
  EXPECT_NE(message.find("--animation"), std::string::npos) << message;
  EXPECT_NE(message.find("0 'slide', 1 'lift', 2 'sink'"), std::string::npos) << message;
}

// A mesh of one triangle with two POSITION morph targets; returns the builder.
gltf_builder morph_triangle(const json& mesh_weights, const json& node_weights, bool sparse_second = false) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int d0 = b.add_positions({0, 0, 1, 0, 0, 2, 0, 0, 0});  // z += 1, 2, 0
  int d1 = -1;
  if (sparse_second) {
    // Zeros except vertex 2: (4, 0, 0), as a sparse accessor without a bufferView.
    const int indices = b.add_view(std::vector<uint16_t>{2, 0}.data(), 2);
    const int values = b.add_view(std::vector<float>{4, 0, 0}.data(), 12);
    d1 = b.add_accessor(-1, k_float, 3, "VEC3");
    b.doc["accessors"][d1]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", indices}, {"componentType", k_ushort}}},
                                        {"values", {{"bufferView", values}}}};
  } else {
    d1 = b.add_positions({4, 0, 0, 0, 0, 0, 4, 0, 0});  // x += 4 on vertices 0 and 2
  }
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2}, k_ushort, "SCALAR", 1);
  json mesh = {{"primitives",
                {{{"attributes", {{"POSITION", pos}}},
                  {"indices", idx},
                  {"targets", {{{"POSITION", d0}}, {{"POSITION", d1}}}}}}}};
  if (!mesh_weights.is_null()) mesh["weights"] = mesh_weights;
  b.doc["meshes"].push_back(mesh);
  json node = {{"mesh", 0}};
  if (!node_weights.is_null()) node["weights"] = node_weights;
  b.add_node(node);
  return b;
}

void expect_position(const mesh& m, size_t v, double x, double y, double z) {
  SCOPED_TRACE(v);
  EXPECT_NEAR(m.positions.at(v).x, x, tol);
  EXPECT_NEAR(m.positions.at(v).y, y, tol);
  EXPECT_NEAR(m.positions.at(v).z, z, tol);
}

TEST(GltfAnimation, AnimationsDrivingTheSameNodesAreOneWarningWithTheCount) {
  temp_folder dir;
  gltf_builder b = triangle_node();
  b.add_node({{"mesh", 0}});
  b.add_node({{"mesh", 0}});
  // Like a rig's clips: "walk" and "run" each drive nodes 0, 1 and 2; "wave" only node 2.
  for (const float step : {1.0f, 2.0f}) {
    const int a = add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, step, 0, 0}, "VEC3", 3);
    json& channels = b.doc["animations"][size_t(a)]["channels"];
    for (const int node : {1, 2})
      channels.push_back({{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}});
  }
  add_animation(b, 2, "translation", {0, 1}, {0, 0, 0, 0, 3, 0}, "VEC3", 3);
  const scene s = load_at(b, dir, 1.0);
  EXPECT_NEAR(translation_of(s, 2).x, 1.0, tol);  // the first animation wins
  std::vector<std::string> overlaps;
  for (const std::string& w : s.stats.warnings)
    if (w.find("both drive") != std::string::npos) overlaps.push_back(w);
  ASSERT_EQ(overlaps.size(), 1u);
  EXPECT_EQ(overlaps[0],
            "4 node properties are driven by more than one animation (animations 0 and 1 both drive "
            "translation of /nodes/0, ...); the first wins (choose one with --animation)");
}

TEST(GltfMorph, MeshDefaultWeightsPoseAStillWithoutAnimation) {
  temp_folder dir;
  const scene s = load_gltf(morph_triangle(json::array({0.5, 0.25}), nullptr).write(dir.file("m.gltf")));
  ASSERT_EQ(s.meshes.size(), 1u);
  // p + 0.5 d0 + 0.25 d1.
  expect_position(s.meshes[0], 0, 1.0, 0.0, 0.5);
  expect_position(s.meshes[0], 1, 1.0, 0.0, 1.0);
  expect_position(s.meshes[0], 2, 1.0, 1.0, 0.0);
  EXPECT_NEAR(s.meshes[0].bounds.upper.z, 1.0, tol);
}

TEST(GltfMorph, NodeWeightsOverrideTheMeshsAndSparseDeltasApply) {
  temp_folder dir;
  const scene s = load_gltf(
      morph_triangle(json::array({0.5, 0.25}), json::array({1.0, 0.5}), true).write(dir.file("m.gltf")));
  expect_position(s.meshes.at(0), 0, 0.0, 0.0, 1.0);
  expect_position(s.meshes.at(0), 1, 1.0, 0.0, 2.0);
  expect_position(s.meshes.at(0), 2, 2.0, 1.0, 0.0);  // the sparse delta's only vertex
}

TEST(GltfMorph, ZeroDefaultWeightsShareTheRestMeshAndAWeightsChannelAnimates) {
  temp_folder dir;
  gltf_builder b = morph_triangle(nullptr, nullptr);
  b.add_node({{"mesh", 0}, {"translation", {5, 0, 0}}});
  // Node 0's weights: (0, 0) at t = 0 to (1, 0.5) at t = 2; node 1 keeps the zero defaults.
  add_animation(b, 0, "weights", {0, 2}, {0, 0, 1, 0.5f}, "SCALAR", 1);
  // A still without the animation: both nodes place the one rest mesh.
  const scene still = load_at(b, dir, 0.0, "none");
  ASSERT_EQ(still.meshes.size(), 1u);
  EXPECT_EQ(still.instances.size(), 2u);
  // At t = 0 the channel's weights are zero, yet node 0 keeps its own mesh (the scene's structure
  // does not change with time), in the rest shape.
  const scene rest = load_at(b, dir, 0.0);
  ASSERT_EQ(rest.meshes.size(), 2u);
  expect_position(rest.meshes[rest.instances.at(0).shape], 0, 0.0, 0.0, 0.0);
  const scene s = load_at(b, dir, 1.0);  // weights (0.5, 0.25)
  ASSERT_EQ(s.meshes.size(), 2u);        // node 0's posed mesh and the shared rest mesh
  expect_position(s.meshes[s.instances.at(0).shape], 0, 1.0, 0.0, 0.5);
  expect_position(s.meshes[s.instances.at(1).shape], 0, 0.0, 0.0, 0.0);
}

// CUBICSPLINE weights store, per key, the in-tangents of every target, then the values, then the
// out-tangents. Keys at 0 and 2 s; at 1 s (u = 1/2, h10 = 1/8, h01 = 1/2, h11 = -1/8):
// w0 = h10·2·1 + h01·1 = 0.75 and w1 = h01·0.5 + h11·2·3 = -0.5.
TEST(GltfMorph, CubicSplineWeightsKeepTheirPerTargetLayout) {
  temp_folder dir;
  gltf_builder b = morph_triangle(nullptr, nullptr);
  add_animation(
      b, 0, "weights", {0, 2},
      {/*key 0: in*/ 9, 9, /*value*/ 0, 0, /*out*/ 1, 0, /*key 1: in*/ 0, 3, /*value*/ 1, 0.5f, /*out*/ 9, 9},
      "SCALAR", 1, "CUBICSPLINE");
  const scene s = load_at(b, dir, 1.0);
  // p + 0.75 d0 - 0.5 d1, d0 = z (1, 2, 0), d1 = x (4, 0, 4).
  expect_position(s.meshes.at(0), 0, -2.0, 0.0, 0.75);
  expect_position(s.meshes.at(0), 1, 1.0, 0.0, 1.5);
  expect_position(s.meshes.at(0), 2, -2.0, 1.0, 0.0);
}

TEST(GltfMorph, WeightsThatDoNotMatchTheTargetsAreRefused) {
  temp_folder dir;
  const std::string message =
      error_of([&] { load_gltf(morph_triangle(json::array({0.5}), nullptr).write(dir.file("m.gltf"))); });
  EXPECT_NE(message.find("/meshes/0/weights"), std::string::npos) << message;
}

// The two-bone arm: joint 0 at the armature's origin, joint 1 one unit along +x, the armature
// lifted to z = 3. Vertices A (0, 0.1) on joint 0, B (1.5, 0) shared with weights 1 and 1 (sum
// 2, renormalized), C (2, 0) and D (2, 0.2) on joint 1, D through the second JOINTS/WEIGHTS set.
// Joint 1 turns about +Z from 0° at t = 0 to 90° at t = 1. The mesh node's own transform must be
// ignored.
gltf_builder skinned_arm(const std::vector<float>& weights0 = {1, 0, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0,
                                                               0},
                         const std::vector<uint8_t>& joints0 = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0,
                                                                0}) {
  gltf_builder b;
  const int pos = b.add_positions({0, 0.1f, 0, 1.5f, 0, 0, 2, 0, 0, 2, 0.2f, 0});
  const int nrm = b.add_data(std::vector<float>{0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1}, k_float, "VEC3", 3);
  const int j0 = b.add_data(joints0, k_ubyte, "VEC4", 4);
  const int w0 = b.add_data(weights0, k_float, "VEC4", 4);
  const int j1 =
      b.add_data(std::vector<uint16_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, k_ushort, "VEC4", 4);
  const int w1 = b.add_data(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 0, 0}, k_ubyte,
                            "VEC4", 4, true);
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2, 1, 3, 2}, k_ushort, "SCALAR", 1);
  json primitive = {{"indices", idx}};
  primitive["attributes"] = {{"POSITION", pos}, {"NORMAL", nrm},  {"JOINTS_0", j0},
                             {"WEIGHTS_0", w0}, {"JOINTS_1", j1}, {"WEIGHTS_1", w1}};
  b.add_mesh(primitive);
  // Inverse bind matrices: joint 0 identity, joint 1 a translation by -1 along x (column-major).
  const int ibm = b.add_data(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,
                                                1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1},
                             k_float, "MAT4", 16);
  b.add_node({{"mesh", 0}, {"skin", 0}, {"translation", {50, 50, 50}}});  // node 0: ignored transform
  const int armature = b.add_node({{"translation", {0, 0, 3}}});
  const int joint0 = b.add_node(json::object());
  const int joint1 = b.add_node({{"translation", {1, 0, 0}}});
  b.add_child(armature, joint0);
  b.add_child(joint0, joint1);
  b.doc["skins"].push_back({{"joints", {joint0, joint1}}, {"inverseBindMatrices", ibm}});
  const float h = std::sqrt(0.5f);
  add_animation(b, joint1, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, h, h}, "VEC4", 4);
  return b;
}

TEST(GltfSkin, TwoBoneArmAtAKnownTimeMatchesTheHandComputedPose) {
  temp_folder dir;
  const gltf_builder b = skinned_arm();
  for (const double t : {0.0, 1.0 / 3.0, 0.5, 1.0}) {
    SCOPED_TRACE(t);
    const scene s = load_at(b, dir, t);
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].world_from_object, dmat4(1.0));  // posed in world space
    const mesh& m = s.meshes.at(s.instances[0].shape);
    const double a = t * pi / 2, c = std::cos(a), sn = std::sin(a);
    // Joint 1's matrix: armature · T(1,0,0) · R(a) · T(-1,0,0); joint 0's: the armature's.
    expect_position(m, 0, 0.0, 0.1, 3.0);
    // B: half joint 0 (1.5, 0) and half joint 1 (1 + 0.5c, 0.5s).
    expect_position(m, 1, (1.5 + 1 + 0.5 * c) / 2, 0.25 * sn, 3.0);
    expect_position(m, 2, 1 + c, sn, 3.0);
    expect_position(m, 3, 1 + c - 0.2 * sn, sn + 0.2 * c, 3.0);
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_NEAR(m.normals[2].x, c, tol);  // C's normal (1, 0, 0) turns with joint 1
    EXPECT_NEAR(m.normals[2].y, sn, tol);
  }
}

// One joint scaled 2x along x (no inverse bind matrices: identity): positions stretch, and the
// normal (1, 1, 0)/√2 goes by the inverse transpose, diag(1/2, 1, 1), to (1, 2, 0)/√5, not
// the stretched (2, 1, 0)/√5 of the matrix itself.
TEST(GltfSkin, NormalsFollowTheInverseTransposeOfTheJointMatrix) {
  temp_folder dir;
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const float h = std::sqrt(0.5f);
  const int nrm = b.add_data(std::vector<float>{h, h, 0, h, h, 0, h, h, 0}, k_float, "VEC3", 3);
  const int joints = b.add_data(std::vector<uint8_t>(12, 0), k_ubyte, "VEC4", 4);
  const int weights = b.add_data(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, k_float, "VEC4", 4);
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2}, k_ushort, "SCALAR", 1);
  json primitive = {{"indices", idx}};
  primitive["attributes"] = {
      {"POSITION", pos}, {"NORMAL", nrm}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}};
  b.add_mesh(primitive);
  b.add_node({{"mesh", 0}, {"skin", 0}});
  const int joint = b.add_node({{"scale", {2, 1, 1}}});
  b.doc["skins"].push_back({{"joints", {joint}}});
  const scene s = load_gltf(b.write(dir.file("scaled.gltf")));
  const mesh& m = s.meshes.at(0);
  expect_position(m, 1, 2.0, 0.0, 0.0);
  expect_position(m, 2, 0.0, 1.0, 0.0);
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_NEAR(m.normals[0].x, 1 / std::sqrt(5.0), tol);
  EXPECT_NEAR(m.normals[0].y, 2 / std::sqrt(5.0), tol);
  EXPECT_NEAR(m.normals[0].z, 0.0, tol);
}

TEST(GltfSkin, BadJointsAndWeightsAreRefusedNamingTheAttribute) {
  temp_folder dir;
  struct bad_case {
    std::vector<float> weights;
    std::vector<uint8_t> joints;
    const char* pointer;
    const char* reason;
  };
  const std::vector<bad_case> cases = {
      {{1, 0, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
       {0, 0, 0, 0, 0, 7, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
       "/meshes/0/primitives/0/attributes/JOINTS_0",
       "vertex 1 names joint 7, but /skins/0 has 2 joints"},
      {{1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
       {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
       "/meshes/0/primitives/0/attributes/WEIGHTS_0",
       "vertex 1's joint weights are all zero"},
      {{1, 0, 0, 0, 1, -1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
       {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
       "/meshes/0/primitives/0/attributes/WEIGHTS_0",
       "vertex 1 has a negative weight"},
  };
  for (const bad_case& c : cases) {
    SCOPED_TRACE(c.reason);
    const gltf_builder b = skinned_arm(c.weights, c.joints);
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find(c.pointer), std::string::npos) << message;
    EXPECT_NE(message.find(c.reason), std::string::npos) << message;
  }
}

TEST(GltfAnimation, BadSamplersAreRefusedNamingThePointer) {
  temp_folder dir;
  {
    gltf_builder b = triangle_node();
    add_animation(b, 0, "translation", {0, 1, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3", 3);
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/samplers/0/input"), std::string::npos) << message;
    EXPECT_NE(message.find("strictly increase"), std::string::npos) << message;
  }
  {
    gltf_builder b = triangle_node();
    add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3", 3);
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/samplers/0/output"), std::string::npos) << message;
    EXPECT_NE(message.find("has 3 elements; 2 keyframes need 2"), std::string::npos) << message;
  }
  {
    gltf_builder b = triangle_node();  // CUBICSPLINE needs three elements a key
    add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", 3, "CUBICSPLINE");
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/samplers/0/output"), std::string::npos) << message;
  }
  {
    gltf_builder b = triangle_node();
    add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", 3, "BEZIER");
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/samplers/0/interpolation"), std::string::npos) << message;
  }
  {
    gltf_builder b = triangle_node({{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
    add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", 3);
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/channels/0/target/node: /nodes/0 has a matrix"), std::string::npos)
        << message;
  }
  {
    gltf_builder b = triangle_node();  // its mesh has no morph targets
    add_animation(b, 0, "weights", {0, 1}, {0, 1}, "SCALAR", 1);
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/channels/0/target/node"), std::string::npos) << message;
    EXPECT_NE(message.find("no mesh with morph targets"), std::string::npos) << message;
  }
  {
    gltf_builder b = triangle_node();
    add_animation(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", 3);
    b.doc["animations"][0]["channels"].push_back(
        {{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}});
    const std::string message = error_of([&] { load_at(b, dir, 0.5); });
    EXPECT_NE(message.find("/animations/0/channels/1/target: a second channel"), std::string::npos)
        << message;
  }
  {
    gltf_builder b = triangle_node();
    const std::string message = error_of([&] { load_at(b, dir, std::nan("")); });
    EXPECT_NE(message.find("--time"), std::string::npos) << message;
  }
  {
    gltf_builder b = triangle_node();
    const std::string message = error_of([&] { load_at(b, dir, 0.0, "walk"); });
    EXPECT_NE(message.find("the file has no animations"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace kiln
