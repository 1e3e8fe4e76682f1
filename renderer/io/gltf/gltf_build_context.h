// What the glTF scene builder shares while it walks a scene's node forest: the parsed model,
// the scene being filled, the caches that let primitives share meshes, and the pose. Internal to
// io/gltf; filled by gltf_loader, read by gltf_primitive_mesh.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/memory_budget.h"
#include "io/gltf/gltf_animation.h"
#include "io/gltf/gltf_common.h"
#include "scene/scene.h"

namespace kiln::gltf_internal {

// What a posed primitive's vertices depend on, so nodes with equal keys share one posed mesh:
// (mesh, primitive, skin or -1, the node when a channel drives its weights or -1, the weights
// otherwise). A skinned mesh is posed in world space by its skin's joints alone, and a morphed
// one in its node's space, which each node's instance places; the key does not change with time.
using pose_key = std::tuple<int, int, int, int, std::vector<double>>;

// Everything the scene builder shares while it walks the node forest.
struct build_context {
  const tinygltf::Model& model;
  const std::string& file;
  size_t max_instances;  // gltf_limits::max_instances
  uint64_t max_texels;   // gltf_limits::max_texels
  int threads;           // image decoding threads (0: all cores)
  bool quantized;        // the file uses KHR_mesh_quantization
  scene& out;
  std::map<std::pair<int, int>, int32_t> mesh_cache;  // (glTF mesh, primitive) -> scene mesh or -1
  std::vector<int> instance_gltf_material;            // per scene instance; -1: default material
  std::set<std::string>& warned;                      // each distinct warning is reported once
  // Primitives built from the same accessors into the same attributes share one scene mesh.
  std::map<std::vector<int>, int32_t> geometry_cache{};
  memory_budget* memory = nullptr;  // gltf_load_options::memory
  // Posing; all empty for an asset without animations, skins and morph weights.
  animation_pose pose{};                             // the chosen animations at the chosen time
  std::vector<dmat4> node_world{};                   // every node's world transform, once a skin needs it
  std::map<int, std::vector<dmat4>> skin_joints{};   // skin -> world(joint) * inverseBindMatrix
  std::vector<char> node_moves{};                    // per node: a channel moves it or an ancestor
  std::map<pose_key, int32_t> posed_cache{};         // a pose -> its scene mesh (-1: nothing)
  std::map<pose_key, int32_t> still_poses{};         // those no animation moves
  std::set<std::pair<int, int>> posed_primitives{};  // (mesh, primitive) built posed
  std::vector<uint32_t> posed_meshes{};              // the scene meshes posed for this time
  uint64_t posed_bytes = 0;                          // what they were charged to the budget
  // A frame of a sequence: the previous frame's scene, its geometry cache and its poses that do
  // not change with time, whose meshes this frame takes over instead of building them again (null
  // for a single load).
  scene* reuse = nullptr;
  const std::map<std::vector<int>, int32_t>* reuse_geometry = nullptr;
  const std::map<pose_key, int32_t>* reuse_poses = nullptr;
};

// How a node deforms its mesh: morph weights (empty: none) and the joint matrices of its skin
// (null: not skinned). `moves`: an animation changes the pose with time (a weights channel on
// the node, or a channel on a joint or a joint's ancestor, whose keys differ), so each time poses
// it anew; a pose that does not move is built once, like a rigid mesh.
struct deformation {
  std::vector<double> weights;
  const std::vector<dmat4>* joints = nullptr;
  int skin = -1;
  bool moves = false;
};

inline void warn_once(build_context& ctx, const std::string& message) {
  if (ctx.warned.insert(message).second) ctx.out.stats.warnings.push_back(message);
}

// /meshes/<mesh>/primitives/<primitive>, where a primitive's errors point.
inline std::string primitive_pointer(int mesh_index, int prim_index) {
  return pointer_join(pointer_join(pointer("meshes", mesh_index), "primitives"), prim_index);
}

}  // namespace kiln::gltf_internal
