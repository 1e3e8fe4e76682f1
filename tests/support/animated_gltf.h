// Small animated scenes for the motion tests (motion vectors and blur): an orthographic camera,
// LINEAR animations, and the moving quads both tests measure.
// Depends on gltf_builder.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "support/gltf_builder.h"

namespace kiln::testing {

// An orthographic camera at z = 5 looking down -z sees x and y in -1..1; its node is returned.
inline int add_camera(gltf_builder& b) {
  const int camera =
      b.add_camera({{"type", "orthographic"},
                    {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 100}}}});
  return b.add_node({{"camera", camera}, {"translation", {0, 0, 5}}});
}

// A LINEAR animation of node's `path` from `from` (t = 0) to `to` (t = 1 s).
inline void animate(gltf_builder& b, int node, const std::string& path, const std::vector<float>& from,
                    const std::vector<float>& to) {
  const int times = b.add_data(std::vector<float>{0, 1}, 5126, "SCALAR", 1);
  std::vector<float> values = from;
  values.insert(values.end(), to.begin(), to.end());
  const std::string type = from.size() == 1 ? "SCALAR" : from.size() == 3 ? "VEC3" : "VEC4";
  const int keys = b.add_data(values, 5126, type, from.size());
  b.doc["animations"].push_back(
      {{"samplers", {{{"input", times}, {"output", keys}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}}}});
}

// Top half: a quad over x -1..0 sliding +1 in x a second. Bottom half: a quad over x -1..-0.5
// whose right edge a morph target moves +1.5 as its weight goes 0 -> 1 in a second.
inline std::string sliding_and_morphing(const std::string& folder) {
  gltf_builder b;
  const int slide = b.add_mesh({{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3});
  animate(b, b.add_node({{"mesh", slide}}), "translation", {0, 0, 0}, {1, 0, 0});
  const int morph = b.add_mesh({{-1, -1, 0}, {-0.5f, -1, 0}, {-0.5f, 0, 0}, {-1, 0, 0}}, {0, 1, 2, 0, 2, 3});
  const int target =
      b.add_data(std::vector<float>{0, 0, 0, 1.5f, 0, 0, 1.5f, 0, 0, 0, 0, 0}, 5126, "VEC3", 3);
  b.doc["meshes"][morph]["primitives"][0]["targets"] = {{{"POSITION", target}}};
  b.doc["meshes"][morph]["weights"] = {0.0};
  animate(b, b.add_node({{"mesh", morph}}), "weights", {0}, {1});
  add_camera(b);
  return b.write(folder + "/slide_morph.gltf");
}

// A unit square about the origin spinning a quarter turn about the view axis in a second (LINEAR
// rotation: slerp, so a constant angular speed).
inline std::string spinning(const std::string& folder) {
  gltf_builder b;
  const int quad = b.add_mesh({{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}},
                              {0, 1, 2, 0, 2, 3});
  const float half_turn = float(std::sqrt(0.5));
  animate(b, b.add_node({{"mesh", quad}}), "rotation", {0, 0, 0, 1}, {0, 0, half_turn, half_turn});
  add_camera(b);
  return b.write(folder + "/spin.gltf");
}

}  // namespace kiln::testing
