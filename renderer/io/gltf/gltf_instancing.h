// EXT_mesh_gpu_instancing: a node's per-instance TRANSLATION, ROTATION and SCALE accessors become
// one transform per instance, so N instances of a mesh cost N transforms (scene.instances), never
// N meshes. Also the node TRS composition both use. Internal to io/gltf; bad values throw
// kiln::error (input) naming the JSON path, e.g.
// /nodes/3/extensions/EXT_mesh_gpu_instancing/attributes/ROTATION.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace kiln::gltf_internal {

constexpr const char* gpu_instancing_extension = "EXT_mesh_gpu_instancing";

// q (x, y, z, w) at unit length, for any finite q but zero (which gives zero): scaled by its largest
// component first, so that (1e200, 0, 0, 0), whose squared length is infinite, stays a half turn
// about x instead of collapsing to zero and the identity.
dvec4 unit_quaternion(const dvec4& q);

// T * R * S from a translation, a quaternion (x, y, z, w; glTF's order, normalised here, must not
// be zero) and a scale: glTF's node transform and each EXT_mesh_gpu_instancing instance.
dmat4 trs_matrix(const dvec3& translation, const dvec4& rotation, const dvec3& scale);

// The node_from_instance transform of every instance the node's EXT_mesh_gpu_instancing object
// defines, or empty when the node has none. Accessor types follow the extension (TRANSLATION and
// SCALE VEC3 FLOAT, ROTATION VEC4 FLOAT or normalized BYTE/SHORT); with `quantized` (the file uses
// KHR_mesh_quantization) TRANSLATION and SCALE may also be 8- or 16-bit integers. All attributes
// must have the same count and finite values. The count is checked before any value is read:
// `placed` scene instances exist already and each glTF instance adds `per_instance` (the mesh's
// primitives); the total must stay within `limit` (gltf_limits::max_instances).
struct instance_budget {
  size_t placed = 0;
  size_t per_instance = 1;
  size_t limit = 0;
};
std::optional<std::vector<dmat4>> read_gpu_instances(const tinygltf::Model& model, int node_index,
                                                     bool quantized, const instance_budget& budget,
                                                     const std::string& file);

}  // namespace kiln::gltf_internal
