// A mesh that skins and morphs, for the tests of shared poses: nodes that pose it alike share one
// posed mesh, and unshared_poses() writes the same asset with a mesh and skin per node as the
// reference sharing must reproduce. Depends on gltf_builder and animated_gltf.
#pragma once

#include <cstdint>
#include <vector>

#include "support/animated_gltf.h"
#include "support/gltf_builder.h"

namespace kiln::testing {

// A strip of `columns` quads from x = 0 to 2, y = 0 to 1 (2 columns + 2 vertices) with two
// POSITION morph targets (z += 1 and y += 0.5 on every vertex) and default weights (0.5, 0.25):
// mesh 0 skinned to two joints (the vertices past x = 1 follow joint 1), mesh 1 the same without
// the skin attributes. Nodes 0 and 1 are the joints, joint 1 at x = 1 turned 30° about +Z, and
// skin 0 binds them; the tests add the nodes that place the meshes.
inline gltf_builder deforming_strip(int columns) {
  gltf_builder b;
  std::vector<float> positions, deltas_z, deltas_y, weights;
  std::vector<uint8_t> joints;
  std::vector<uint32_t> indices;
  for (int i = 0; i <= columns; ++i)
    for (int j = 0; j < 2; ++j) {
      const float x = 2.0f * float(i) / float(columns);
      positions.insert(positions.end(), {x, float(j), 0.0f});
      deltas_z.insert(deltas_z.end(), {0.0f, 0.0f, 1.0f});
      deltas_y.insert(deltas_y.end(), {0.0f, 0.5f, 0.0f});
      joints.insert(joints.end(), {uint8_t(x > 1.0f ? 1 : 0), 0, 0, 0});
      weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
  for (uint32_t i = 0; i < uint32_t(columns); ++i)
    indices.insert(indices.end(), {2 * i, 2 * i + 2, 2 * i + 3, 2 * i, 2 * i + 3, 2 * i + 1});
  nlohmann::json primitive = {{"indices", b.add_data(indices, 5125, "SCALAR", 1)}};
  primitive["attributes"] = {{"POSITION", b.add_positions(positions)}};
  primitive["targets"] = {{{"POSITION", b.add_positions(deltas_z)}},
                          {{"POSITION", b.add_positions(deltas_y)}}};
  nlohmann::json skinned = primitive;
  skinned["attributes"]["JOINTS_0"] = b.add_data(joints, 5121, "VEC4", 4);
  skinned["attributes"]["WEIGHTS_0"] = b.add_data(weights, 5126, "VEC4", 4);
  for (const nlohmann::json& p : {skinned, primitive})
    b.doc["meshes"][b.add_mesh(p)]["weights"] = {0.5, 0.25};
  const int joint0 = b.add_node(nlohmann::json::object());
  const int joint1 = b.add_node({{"translation", {1, 0, 0}}, {"rotation", {0, 0, 0.258819, 0.965926}}});
  b.add_child(joint0, joint1);
  // Joint 1's inverse bind matrix undoes its rest place, x = 1 (column-major).
  const int ibm = b.add_data(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,
                                                1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1},
                             5126, "MAT4", 16);
  b.doc["skins"].push_back({{"joints", {joint0, joint1}}, {"inverseBindMatrices", ibm}});
  return b;
}

// The same asset with a mesh (and a skin) of its own for every node that places one: nothing can
// be shared, so it is the reference that sharing must reproduce.
inline gltf_builder unshared_poses(gltf_builder b) {
  const nlohmann::json meshes = b.doc["meshes"], skins = b.doc["skins"];
  for (nlohmann::json& node : b.doc["nodes"]) {
    if (!node.contains("mesh")) continue;
    const int mesh = node["mesh"];
    node["mesh"] = b.doc["meshes"].size();
    b.doc["meshes"].push_back(meshes[size_t(mesh)]);
    if (!node.contains("skin")) continue;
    const int skin = node["skin"];
    node["skin"] = b.doc["skins"].size();
    b.doc["skins"].push_back(skins[size_t(skin)]);
  }
  return b;
}

// Adds `count` nodes placing `mesh` 0 (skinned, with skin 0) or 1 (morphed), node n at z = -3n
// (which a skin ignores), each with the JSON members of `extra`.
inline void add_strip_nodes(gltf_builder& b, int mesh, int count,
                            const nlohmann::json& extra = nlohmann::json::object()) {
  for (int n = 0; n < count; ++n) {
    nlohmann::json node = {{"mesh", mesh}, {"translation", {0, 0, -3 * n}}};
    if (mesh == 0) node["skin"] = 0;
    for (auto& [key, value] : extra.items()) node[key] = value;
    b.add_node(node);
  }
}

// Turns joint 1 a further 30° over the first second (LINEAR rotation): the skin's pose moves.
inline void bend_strip(gltf_builder& b) {
  animate(b, 1, "rotation", {0, 0, 0.258819f, 0.965926f}, {0, 0, 0.5f, 0.866025f});
}

}  // namespace kiln::testing
