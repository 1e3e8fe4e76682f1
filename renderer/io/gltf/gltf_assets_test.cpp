// The optional asset suite: Khronos sample models must load with the triangle counts listed in
// ../shared/assets/README.md, and every file of the glTF-Validator invalid corpus must either
// get the outcome gltf_invalid_corpus_table.h names (a refusal at a JSON pointer, or a load with a
// warning), never crash; the ones whose damage makes rendering unsafe must throw.
// Skips when ../shared/assets is absent (the project's own tests must pass without it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "io/gltf/gltf_invalid_corpus_table.h"
#include "io/gltf/gltf_loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const fs::path assets = KILN_SHARED_ASSETS;

size_t scene_triangles(const scene& s) {
  size_t total = 0;
  for (const instance& inst : s.instances) total += s.meshes.at(inst.shape).triangle_count();
  return total;
}

size_t unique_triangles(const scene& s) {
  size_t total = 0;
  for (const mesh& m : s.meshes) total += m.triangle_count();
  return total;
}

struct asset_case {
  const char* file;
  size_t scene_tris;
  size_t unique_tris;
};

TEST(GltfAssets, SampleModelsLoadWithExpectedTriangleCounts) {
  if (!fs::exists(assets / "README.md")) GTEST_SKIP() << "no sample assets at " << assets;
  const asset_case cases[] = {
      {"Box/glTF-Binary/Box.glb", 12, 12},
      {"BoxTextured/glTF/BoxTextured.gltf", 12, 12},
      {"BoxInterleaved/glTF-Binary/BoxInterleaved.glb", 12, 12},
      {"Triangle/glTF/Triangle.gltf", 1, 1},
      {"SimpleMeshes/glTF/SimpleMeshes.gltf", 2, 1},
      {"MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf", 16, 16},
      {"SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf", 12, 12},
      {"Cameras/glTF/Cameras.gltf", 2, 2},
      // Its meshes repeat primitives on the same accessors: one scene mesh each (3884 declared).
      {"NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb", 7724, 1324},
      {"2CylinderEngine/glTF-Binary/2CylinderEngine.glb", 121496, 75730},
      {"ToyCar/glTF/ToyCar.gltf", 108936, 108936},
      {"SimpleInstancing/glTF-Binary/SimpleInstancing.glb", 1500, 12},
      {"Duck/glTF-Binary/Duck.glb", 4212, 4212},
      {"Duck/glTF-Quantized/Duck.gltf", 4212, 4212},
  };
  for (const asset_case& c : cases) {
    SCOPED_TRACE(c.file);
    const fs::path path = assets / c.file;
    if (!fs::exists(path)) {
      ADD_FAILURE() << "missing sample model " << path;
      continue;
    }
    scene s;
    try {
      s = load_gltf(path.string());
    } catch (const kiln::error& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    // A dropped degenerate triangle is still a triangle of the file: count it back in when
    // comparing with the README, which counts what the file declares.
    EXPECT_EQ(unique_triangles(s) + s.stats.degenerate_triangles_dropped, c.unique_tris);
    if (s.stats.degenerate_triangles_dropped == 0) {
      EXPECT_EQ(scene_triangles(s), c.scene_tris);
    }
    EXPECT_FALSE(s.materials.empty());
  }
}

TEST(GltfAssets, SampleModelDetails) {
  if (!fs::exists(assets / "README.md")) GTEST_SKIP() << "no sample assets at " << assets;
  const scene simple = load_gltf((assets / "SimpleMeshes/glTF/SimpleMeshes.gltf").string());
  EXPECT_EQ(simple.meshes.size(), 1u);
  EXPECT_EQ(simple.instances.size(), 2u);
  EXPECT_EQ(simple.materials.size(), 1u);  // the default material

  const scene modes = load_gltf((assets / "MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf").string());
  EXPECT_EQ(modes.stats.non_triangle_primitives_skipped, 4u);

  const scene cameras = load_gltf((assets / "Cameras/glTF/Cameras.gltf").string());
  ASSERT_EQ(cameras.cameras.size(), 2u);
  EXPECT_EQ(cameras.cameras[0].kind, projection::perspective);
  EXPECT_EQ(cameras.cameras[1].kind, projection::orthographic);

  const scene textured = load_gltf((assets / "BoxTextured/glTF/BoxTextured.gltf").string());
  ASSERT_EQ(textured.images.size(), 1u);
  EXPECT_GT(textured.images[0].width, 0);
  EXPECT_EQ(textured.images[0].texels8.size(), static_cast<size_t>(textured.images[0].width) *
                                                   static_cast<size_t>(textured.images[0].height) * 4);
  ASSERT_EQ(textured.meshes.size(), 1u);
  EXPECT_EQ(textured.meshes[0].texcoords0.size(), textured.meshes[0].positions.size());

  // The node-less Box.glb uses a matrix on its root node: the instance must carry it.
  const scene box = load_gltf((assets / "Box/glTF-Binary/Box.glb").string());
  ASSERT_EQ(box.instances.size(), 1u);
  EXPECT_NE(box.instances[0].world_from_object, dmat4(1.0));
}

TEST(GltfAssets, SimpleInstancingIsOneMeshPlacedPerInstance) {
  const fs::path path = assets / "SimpleInstancing/glTF-Binary/SimpleInstancing.glb";
  if (!fs::exists(path)) GTEST_SKIP() << "no sample assets at " << assets;
  const scene s = load_gltf(path.string());
  EXPECT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 125u);  // the README's 5 x 5 x 5 grid
  EXPECT_TRUE(s.stats.warnings.empty()) << s.stats.warnings.front();
  // TRANSLATION spans 0..10 on each axis; SCALE 1..2 and ROTATION turn the unit cubes around it.
  const bounds3 world = world_bounds(s);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_GT(world.upper[axis], 10.0);
    EXPECT_LT(world.upper[axis], 10.0 + 2.0 * std::sqrt(3.0));
    EXPECT_LT(world.lower[axis], 0.5);
  }
}

// KHR_mesh_quantization: the quantized Duck (SHORT positions under a dequantizing node scale,
// BYTE normals, UNSIGNED_SHORT UVs dequantized by KHR_texture_transform) matches the float Duck.
TEST(GltfAssets, QuantizedDuckMatchesTheFloatDuck) {
  const fs::path quantized_path = assets / "Duck/glTF-Quantized/Duck.gltf";
  if (!fs::exists(quantized_path)) GTEST_SKIP() << "no sample assets at " << assets;
  const scene plain = load_gltf((assets / "Duck/glTF-Binary/Duck.glb").string());
  const scene quantized = load_gltf(quantized_path.string());
  ASSERT_EQ(plain.instances.size(), 1u);
  ASSERT_EQ(quantized.instances.size(), 1u);
  // One position step is the quantized node's scale (1.01e-4 in world units).
  const double step = quantized.instances[0].world_from_object[0][0];
  EXPECT_NEAR(step, 0.000101006161, 1e-9);
  const bounds3 a = world_bounds(plain), b = world_bounds(quantized);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(a.lower[axis], b.lower[axis], step) << axis;
    EXPECT_NEAR(a.upper[axis], b.upper[axis], step) << axis;
  }

  // The two files order their vertices differently, so pair each quantized vertex with the float
  // vertices at the same world position (within a step) and compare the UVs the renderer samples
  // (KHR_texture_transform applied) with the closest of them.
  const mesh& pm = plain.meshes.at(0);
  const mesh& qm = quantized.meshes.at(0);
  const texture_ref& qref = quantized.materials.at(quantized.instances[0].material).base_color_texture;
  const texture_ref& pref = plain.materials.at(plain.instances[0].material).base_color_texture;
  ASSERT_EQ(qm.texcoords0.size(), qm.positions.size());
  ASSERT_EQ(pm.texcoords0.size(), pm.positions.size());
  ASSERT_EQ(qref.rotation, 0.0f);
  ASSERT_EQ(pref.uv_scale, vec2(1.0f));
  const float uv_step = std::max(qref.uv_scale.x, qref.uv_scale.y);  // 2.3e-4
  double worst_uv = 0.0;
  size_t unmatched = 0;
  for (size_t i = 0; i < qm.positions.size(); ++i) {
    const dvec3 qp = transform_point(quantized.instances[0].world_from_object, dvec3(qm.positions[i]));
    const vec2 quv = qm.texcoords0[i] * qref.uv_scale + qref.offset;
    double best = 1e9;
    for (size_t j = 0; j < pm.positions.size(); ++j) {
      const dvec3 pp = transform_point(plain.instances[0].world_from_object, dvec3(pm.positions[j]));
      if (glm::length(pp - qp) > 1.5 * step) continue;
      best = std::min(best, double(glm::length(quv - (pm.texcoords0[j] + pref.offset))));
    }
    if (best == 1e9)
      ++unmatched;
    else
      worst_uv = std::max(worst_uv, best);
  }
  EXPECT_EQ(unmatched, 0u);
  EXPECT_LT(worst_uv, uv_step);
  // Normals: normalized BYTE decodes to unit vectors.
  for (const vec3& n : qm.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST(GltfAssets, DracoBoxLoadsLikeTheBinaryBox) {
  const fs::path draco = assets / "Box/glTF-Draco/Box.gltf", plain = assets / "Box/glTF-Binary/Box.glb";
  if (!fs::exists(draco)) GTEST_SKIP() << "no sample assets at " << assets;
  const scene d = load_gltf(draco.string()), p = load_gltf(plain.string());
  ASSERT_EQ(d.meshes.size(), 1u);
  EXPECT_EQ(d.meshes[0].triangle_count(), 12u);
  EXPECT_EQ(d.meshes[0].normals.size(), d.meshes[0].positions.size());
  // Draco quantises positions to 14 bits over the box: a step of 1/16384 of its size.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(d.meshes[0].bounds.lower[k], p.meshes[0].bounds.lower[k], 1e-4);
    EXPECT_NEAR(d.meshes[0].bounds.upper[k], p.meshes[0].bounds.upper[k], 1e-4);
  }
}

// Reads INDEX.md's table: file -> expected validator error codes.
std::map<std::string, std::string> invalid_index(const fs::path& index) {
  std::map<std::string, std::string> codes;
  std::ifstream in(index);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    const size_t a = line.find('|', 1);
    if (a == std::string::npos) continue;
    const size_t b = line.find('|', a + 1);
    if (b == std::string::npos) continue;
    std::string file = line.substr(2, a - 3);
    if (file.find(".gl") == std::string::npos) continue;
    codes[file] = line.substr(a + 1, b - a - 1);
  }
  return codes;
}

// The damage classes that make a render wrong or unsafe: these files must be refused.
bool must_refuse(const std::string& file, const std::string& codes) {
  for (const char* code : {"IO_ERROR", "UNRESOLVED_REFERENCE", "ACCESSOR_INDEX_OOB", "GLB_", "INVALID_JSON",
                           "BUFFER_", "ACCESSOR_TOO_LONG", "NODE_LOOP"})
    if (codes.find(code) != std::string::npos) return true;
  return file.find("infinite_transform") != std::string::npos;
}

// Every file gets the outcome its row in gltf_invalid_corpus_table.h names; a refusal is one line
// naming the file, and files the validator's INDEX marks as fatal are never loaded.
TEST(GltfAssets, InvalidCorpusFilesGetTheirExpectedOutcome) {
  const fs::path root = assets / "invalid";
  if (!fs::exists(root)) GTEST_SKIP() << "no invalid corpus at " << root;
  const auto index = invalid_index(root / "INDEX.md");
  EXPECT_GT(index.size(), 50u);
  std::map<std::string, const gltf_test::corpus_expectation*> expected;
  for (const auto& row : gltf_test::invalid_corpus_expectations()) expected[row.file] = &row;
  size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".gltf" && ext != ".glb")) continue;
    ++files;
    const std::string relative = fs::relative(entry.path(), root).generic_string();
    SCOPED_TRACE(relative);
    auto row = expected.find(relative);
    ASSERT_NE(row, expected.end()) << "no expected outcome for " << relative;
    const gltf_test::corpus_expectation& want = *row->second;
    try {
      const scene s = load_gltf(entry.path().string());
      EXPECT_EQ(want.result, gltf_test::outcome::load)
          << "loaded; expected refusal at '" << want.location << "'";
      EXPECT_FALSE(s.materials.empty());
      bool warned = false;
      for (const std::string& warning : s.stats.warnings)
        warned = warned || warning.find(want.fragment) != std::string::npos;
      EXPECT_TRUE(warned) << "no warning contains '" << want.fragment << "'";
    } catch (const kiln::error& e) {
      const std::string message = e.what();
      EXPECT_EQ(want.result, gltf_test::outcome::refuse) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_EQ(message.rfind(entry.path().string(), 0), 0u) << message;
      EXPECT_EQ(e.location().rfind(want.location, 0), 0u) << message;
      EXPECT_NE(e.reason().find(want.fragment), std::string::npos) << message;
      // Only damage to the container or the JSON text itself has no value to point at; what
      // tinygltf would refuse in its own words (no path) is checked before it parses.
      const bool about_the_text =
          e.reason().rfind("GLB:", 0) == 0 || e.reason().find("JSON") != std::string::npos;
      EXPECT_TRUE(!e.location().empty() || about_the_text) << "refused without a JSON pointer: " << message;
    }
    auto it = index.find(relative);
    if (it != index.end() && must_refuse(relative, it->second)) {
      EXPECT_EQ(want.result, gltf_test::outcome::refuse)
          << relative << " (" << it->second << ") must be refused";
    }
  }
  EXPECT_EQ(files, 77u);
  EXPECT_EQ(expected.size(), files);
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

// World-space bounds of every vertex the scene places (tighter than world_bounds' boxes).
bounds3 vertex_bounds(const scene& s) {
  bounds3 b;
  for (const instance& inst : s.instances) {
    if (inst.kind != shape_kind::mesh) continue;
    for (const vec3& p : s.meshes[inst.shape].positions)
      b.extend(transform_point(inst.world_from_object, dvec3(p)));
  }
  return b;
}

// The sum of every placed vertex's world position: any motion of any vertex changes it.
dvec3 vertex_sum(const scene& s) {
  dvec3 sum(0.0);
  for (const instance& inst : s.instances)
    if (inst.kind == shape_kind::mesh)
      for (const vec3& p : s.meshes[inst.shape].positions)
        sum += transform_point(inst.world_from_object, dvec3(p));
  return sum;
}

scene load_posed(const fs::path& path, double time, const std::string& animation = "") {
  gltf_load_options options;
  options.time = time;
  options.animation = animation;
  return load_gltf(path.string(), options);
}

// Every animated, skinned and morphed sample model poses at several times (and in its rest pose,
// --animation none) with finite bounds, and every animated one moves.
TEST(GltfAssets, AnimatedSkinnedAndMorphedModelsPoseAtSeveralTimes) {
  if (!fs::exists(assets / "README.md")) GTEST_SKIP() << "no sample assets at " << assets;
  const std::pair<const char*, bool> files[] = {
      {"SimpleMorph/glTF/SimpleMorph.gltf", true},
      {"AnimatedMorphSphere/glTF-Binary/AnimatedMorphSphere.glb", true},
      {"MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb", false},  // default weights, no animation
      {"SimpleSkin/glTF/SimpleSkin.gltf", true},
      {"RiggedSimple/glTF-Binary/RiggedSimple.glb", true},
      {"RiggedFigure/glTF-Binary/RiggedFigure.glb", true},
      {"CesiumMan/glTF-Binary/CesiumMan.glb", true},
      {"BrainStem/glTF-Binary/BrainStem.glb", true},
      {"RecursiveSkeletons/glTF-Binary/RecursiveSkeletons.glb", true},
      {"InterpolationTest/glTF-Binary/InterpolationTest.glb", true},
      {"BoxAnimated/glTF-Binary/BoxAnimated.glb", true},
      {"AnimatedCube/glTF/AnimatedCube.gltf", true},
      {"AnimatedTriangle/glTF/AnimatedTriangle.gltf", true},
  };
  for (const auto& [file, animated] : files) {
    SCOPED_TRACE(file);
    const fs::path path = assets / file;
    bool moved = false;
    dvec3 first_sum(0.0);
    for (const double t : {-1.0, 0.0, 0.3, 0.5, 1.0, 1.7}) {
      SCOPED_TRACE(t);
      scene s;
      try {
        s = load_posed(path, std::max(t, 0.0), t < 0 ? "none" : "");  // -1: the rest pose
      } catch (const kiln::error& e) {
        ADD_FAILURE() << e.what();
        continue;
      }
      EXPECT_TRUE(s.stats.warnings.empty()) << s.stats.warnings.front();
      const bounds3 b = vertex_bounds(s);
      ASSERT_FALSE(b.empty());
      EXPECT_TRUE(is_finite(b.lower) && is_finite(b.upper));
      const dvec3 sum = vertex_sum(s);
      if (t == 0.0) first_sum = sum;
      if (t > 0.0) moved |= glm::length(sum - first_sum) > 1e-6 * (1.0 + glm::length(first_sum));
    }
    EXPECT_EQ(moved, animated);
  }
}

void expect_bounds(const bounds3& b, dvec3 lower, dvec3 upper, double tolerance) {
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(b.lower[axis], lower[axis], tolerance) << "axis " << axis;
    EXPECT_NEAR(b.upper[axis], upper[axis], tolerance) << "axis " << axis;
  }
}

// Poses whose bounds follow from the models' documented animations.
TEST(GltfAssets, PosedBoundsFollowTheAnimations) {
  if (!fs::exists(assets / "README.md")) GTEST_SKIP() << "no sample assets at " << assets;
  // AnimatedTriangle turns a quarter about +Z every 0.25 s: at 0.5 s the unit right triangle
  // at the origin has turned 180°.
  expect_bounds(vertex_bounds(load_posed(assets / "AnimatedTriangle/glTF/AnimatedTriangle.gltf", 0.5)),
                dvec3(-1, -1, 0), dvec3(0, 0, 0), 1e-6);
  // SimpleSkin: a 1 x 2 strip (x -0.5..0.5, y 0..2) whose upper joint, at y = 1, has turned 90°
  // about +Z at 1 s: the upper half lies over x -1..0, y 0.5..1.5, the lower half stays.
  expect_bounds(vertex_bounds(load_posed(assets / "SimpleSkin/glTF/SimpleSkin.gltf", 1.0)), dvec3(-1, 0, 0),
                dvec3(0.5, 1.5, 0), 1e-5);
  expect_bounds(vertex_bounds(load_posed(assets / "SimpleSkin/glTF/SimpleSkin.gltf", 0.0, "none")),
                dvec3(-0.5, 0, 0), dvec3(0.5, 2, 0), 1e-6);
  // CesiumMan: the bind pose is a T-pose (arms along x, span over 1 m); walking at 0.5 s its arms
  // hang (span under 0.5 m) while its height stays within 3%.
  const bounds3 bind = vertex_bounds(load_posed(assets / "CesiumMan/glTF-Binary/CesiumMan.glb", 0.0, "none"));
  const bounds3 walk = vertex_bounds(load_posed(assets / "CesiumMan/glTF-Binary/CesiumMan.glb", 0.5));
  EXPECT_GT(bind.upper.x - bind.lower.x, 1.0);
  EXPECT_LT(walk.upper.x - walk.lower.x, 0.5);
  EXPECT_NEAR(walk.upper.y - walk.lower.y, bind.upper.y - bind.lower.y, 0.03 * (bind.upper.y - bind.lower.y));
}

}  // namespace
}  // namespace kiln
