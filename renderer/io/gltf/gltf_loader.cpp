// load_gltf: parse (gltf_parse), validate everything (gltf_validate), then build the scene:
// sample the chosen animations at the requested time (gltf_animation), flatten the chosen scene's
// node forest to double-precision world transforms, build each (mesh, primitive) pair once as a
// triangle mesh, place one instance per node that uses it, and convert the materials, lights and
// cameras the scene uses. A node whose mesh is skinned or morphed (non-zero or animated weights)
// gets its own posed copy of each primitive; every other mesh is built once and shared, as in a still asset.
#include "io/gltf/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>

#include "core/error.h"
#include "core/format_number.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_animation.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_draco.h"
#include "io/gltf/gltf_instancing.h"
#include "io/gltf/gltf_materials.h"
#include "io/gltf/gltf_memory.h"
#include "io/gltf/gltf_meshopt.h"
#include "io/gltf/gltf_parse.h"
#include "io/gltf/gltf_quadrics.h"
#include "io/gltf/gltf_validate.h"
#include "io/gltf/gltf_variants.h"
#include "io/gltf/mesh_tangents.h"
#include "scene/coordinate_range.h"

namespace kiln {
namespace {

using namespace gltf_internal;

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
  std::map<std::vector<int>, int32_t> geometry_cache;
  memory_budget* memory = nullptr;  // gltf_load_options::memory
  // Posing; all empty for an asset without animations, skins and morph weights.
  animation_pose pose;                                 // the chosen animations at the chosen time
  std::vector<dmat4> node_world;                       // every node's world transform, once a skin needs it
  std::map<int, std::vector<dmat4>> skin_joints;       // skin -> world(joint) * inverseBindMatrix
  std::map<std::pair<int, int>, int32_t> posed_cache;  // (node, primitive) -> its posed scene mesh
  std::set<std::pair<int, int>> posed_primitives;      // (mesh, primitive) built posed
  std::vector<uint32_t> posed_meshes;                  // the scene meshes built posed
  uint64_t posed_bytes = 0;                            // what they were charged to the budget
  // A frame of a sequence: the previous frame's scene and its geometry cache, whose rigid meshes
  // this frame takes over instead of building them again (null for a single load).
  scene* reuse = nullptr;
  const std::map<std::vector<int>, int32_t>* reuse_geometry = nullptr;
};

// How a node deforms its mesh: morph weights (empty: none) and the joint matrices of its skin
// (null: not skinned).
struct deformation {
  std::vector<double> weights;
  const std::vector<dmat4>* joints = nullptr;
  int skin = -1;
};

void warn_once(build_context& ctx, const std::string& message) {
  if (ctx.warned.insert(message).second) ctx.out.stats.warnings.push_back(message);
}

// A node's parent_from_node: its matrix (column-major), or T * R * S.
dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<size_t>(c * 4 + r)];
    return m;
  }
  const auto& t = node.translation;
  const auto& r = node.rotation;  // validation refused a zero quaternion
  const auto& s = node.scale;
  return trs_matrix(t.size() == 3 ? dvec3(t[0], t[1], t[2]) : dvec3(0.0),
                    r.size() == 4 ? dvec4(r[0], r[1], r[2], r[3]) : dvec4(0, 0, 0, 1),
                    s.size() == 3 ? dvec3(s[0], s[1], s[2]) : dvec3(1.0));
}

// A node's parent_from_node in the pose: the animated TRS when a channel drives it.
dmat4 posed_local(const build_context& ctx, int node_index) {
  if (!ctx.pose.empty()) {
    const animated_node& a = ctx.pose.nodes[static_cast<size_t>(node_index)];
    if (a.transform) return trs_matrix(a.translation, a.rotation, a.scale);
  }
  return local_transform(ctx.model.nodes[static_cast<size_t>(node_index)]);
}

// What a range problem of a node's world transform points at: the node's own matrix, translation
// or scale when that alone is out of range, else the node itself (its parents' transforms share
// the blame).
std::string range_pointer(const tinygltf::Node& node, int node_index) {
  const std::string base = pointer("nodes", node_index);
  if (node.matrix.size() == 16)
    return transform_range_problem(local_transform(node)) ? pointer_join(base, "matrix") : base;
  const auto& t = node.translation;
  if (t.size() == 3 && !(std::max({std::abs(t[0]), std::abs(t[1]), std::abs(t[2])}) <= max_coordinate))
    return pointer_join(base, "translation");
  const auto& s = node.scale;
  if (s.size() == 3 &&
      transform_range_problem(trs_matrix(dvec3(0.0), dvec4(0, 0, 0, 1), dvec3(s[0], s[1], s[2]))))
    return pointer_join(base, "scale");
  return base;
}

// Refuses a world position (camera, light) beyond max_coordinate; the node names the culprit.
void check_node_position(build_context& ctx, int node_index, const dmat4& world, const char* what) {
  const double reach = std::max({std::abs(world[3][0]), std::abs(world[3][1]), std::abs(world[3][2])});
  if (reach <= max_coordinate) return;
  throw input_error(ctx.file, range_pointer(ctx.model.nodes[static_cast<size_t>(node_index)], node_index),
                    std::string("the ") + what + " lies at " + format_coordinate(reach) +
                        ", beyond kiln's coordinate limit of " + format_coordinate(max_coordinate));
}

std::string primitive_pointer(int mesh_index, int prim_index) {
  return pointer_join(pointer_join(pointer("meshes", mesh_index), "primitives"), prim_index);
}

// Reads a float attribute and refuses NaN or infinity (they would poison bounds and traversal).
std::vector<float> read_finite(build_context& ctx, int accessor, const std::string& where,
                               const std::string& name) {
  std::vector<float> values = read_accessor_floats(ctx.model, accessor, ctx.file);
  const size_t components = component_count(ctx.model.accessors[static_cast<size_t>(accessor)].type);
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw input_error(ctx.file, where,
                        name + " element " + std::to_string(i / components) + " of accessor " +
                            std::to_string(accessor) + " is NaN or infinite");
  return values;
}

// The primitive's vertex indices in its own topology (sequential when it has no indices).
std::vector<uint32_t> primitive_indices(build_context& ctx, const tinygltf::Primitive& prim,
                                        size_t vertex_count, const std::string& where) {
  if (prim.indices < 0) {
    std::vector<uint32_t> sequential(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) sequential[i] = static_cast<uint32_t>(i);
    return sequential;
  }
  std::vector<uint32_t> indices = read_accessor_indices(ctx.model, prim.indices, ctx.file);
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= vertex_count)
      throw input_error(ctx.file, pointer_join(where, "indices"),
                        "index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                            " is out of range (POSITION has " + std::to_string(vertex_count) + " vertices)");
  return indices;
}

// Triangle lists from TRIANGLES, TRIANGLE_STRIP (alternate triangles swap two vertices so all
// keep the strip's winding, glTF spec 3.7.2.1) and TRIANGLE_FAN.
std::vector<uint32_t> to_triangle_list(build_context& ctx, const std::vector<uint32_t>& idx, int mode,
                                       const std::string& where) {
  std::vector<uint32_t> tris;
  const size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0)
      warn_once(ctx, where + ": index count is not a multiple of 3; the last indices are ignored");
    tris.assign(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(n / 3 * 3));
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i) {
      const bool odd = i % 2 == 1;
      tris.insert(tris.end(), {idx[i], idx[odd ? i + 2 : i + 1], idx[odd ? i + 1 : i + 2]});
    }
  } else {  // TRIANGLE_FAN
    for (size_t i = 1; i + 1 < n; ++i) tris.insert(tris.end(), {idx[0], idx[i], idx[i + 1]});
  }
  return tris;
}

// A morph target or skin attribute's accessor: `type`, one element per vertex.
void check_vertex_accessor(build_context& ctx, int accessor, int type, size_t vertex_count,
                           const std::string& where, const std::string& expected_format, bool format_ok) {
  const tinygltf::Accessor& acc = ctx.model.accessors[static_cast<size_t>(accessor)];
  if (acc.type != type || !format_ok)
    throw input_error(ctx.file, where,
                      "must be " + expected_format + " (got " + type_name(acc.type) + " " +
                          component_type_name(acc.componentType) + (acc.normalized ? " normalized" : "") +
                          ")");
  if (acc.count != vertex_count)
    throw input_error(ctx.file, where,
                      "accessor has " + std::to_string(acc.count) + " elements but POSITION has " +
                          std::to_string(vertex_count));
}

bool is_float_or_normalized_integer(const tinygltf::Accessor& acc) {
  const int ct = acc.componentType;
  return ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
         (acc.normalized &&
          (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
}

// NORMAL and TANGENT of a posed primitive, as read from its accessors (empty when absent), after
// the deformation.
struct posed_attributes {
  std::vector<float> normals;   // 3 per vertex
  std::vector<float> tangents;  // 4 per vertex
};

// Deforms a primitive's vertices as glTF 2.0 §3.7.2.2 and §3.7.3 say: morph targets first
// (POSITION, NORMAL and TANGENT deltas times the weights), then skinning: each vertex by the
// weighted sum of its joints' matrices (weights renormalized when they do not sum to 1), normals
// by that matrix's inverse transpose, tangents by the matrix itself (tangents are directions in
// the surface; the two agree for rigid joints).
posed_attributes pose_primitive(build_context& ctx, const tinygltf::Primitive& prim, const std::string& where,
                                const deformation& d, std::vector<vec3>& positions) {
  const std::string attributes = pointer_join(where, "attributes");
  const size_t n = positions.size();
  std::vector<dvec3> p(positions.begin(), positions.end());
  std::vector<dvec3> normals, tangents;
  posed_attributes out;
  auto normal = prim.attributes.find("NORMAL");
  if (normal != prim.attributes.end()) {
    out.normals = read_finite(ctx, normal->second, pointer_join(attributes, "NORMAL"), "NORMAL");
    normals.resize(n);
    for (size_t i = 0; i < n; ++i)
      normals[i] = dvec3(out.normals[3 * i], out.normals[3 * i + 1], out.normals[3 * i + 2]);
  }
  auto tangent = prim.attributes.find("TANGENT");
  if (tangent != prim.attributes.end()) {
    out.tangents = read_finite(ctx, tangent->second, pointer_join(attributes, "TANGENT"), "TANGENT");
    tangents.resize(n);
    for (size_t i = 0; i < n; ++i)
      tangents[i] = dvec3(out.tangents[4 * i], out.tangents[4 * i + 1], out.tangents[4 * i + 2]);
  }

  for (size_t t = 0; t < d.weights.size() && t < prim.targets.size(); ++t) {
    const double w = d.weights[t];
    if (w == 0.0) continue;
    const std::string target_at = pointer_join(pointer_join(where, "targets"), static_cast<int64_t>(t));
    for (const auto& [name, accessor] : prim.targets[t]) {
      std::vector<dvec3>* into = name == "POSITION"  ? &p
                                 : name == "NORMAL"  ? &normals
                                 : name == "TANGENT" ? &tangents
                                                     : nullptr;
      if (into == nullptr || into->empty()) continue;  // other targets, or deltas of an attribute it lacks
      const std::string at = pointer_join(target_at, name);
      const tinygltf::Accessor& acc = ctx.model.accessors[static_cast<size_t>(accessor)];
      // KHR_mesh_quantization also allows 8- and 16-bit deltas that are not normalized.
      const bool quantized_ok = ctx.quantized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                                  acc.componentType == TINYGLTF_COMPONENT_TYPE_SHORT);
      check_vertex_accessor(ctx, accessor, TINYGLTF_TYPE_VEC3, n, at,
                            ctx.quantized ? "VEC3 FLOAT, BYTE or SHORT" : "VEC3 FLOAT or normalized integers",
                            is_float_or_normalized_integer(acc) || quantized_ok);
      const std::vector<float> delta = read_finite(ctx, accessor, at, "morph target " + name);
      for (size_t i = 0; i < n; ++i)
        (*into)[i] += w * dvec3(delta[3 * i], delta[3 * i + 1], delta[3 * i + 2]);
    }
  }

  if (d.joints != nullptr) {
    const std::vector<dmat4>& joints = *d.joints;
    const std::string skin = pointer("skins", d.skin);
    std::vector<std::vector<float>> joint_sets, weight_sets;
    std::vector<std::string> weight_at;
    for (int set = 0;; ++set) {
      const std::string jname = "JOINTS_" + std::to_string(set), wname = "WEIGHTS_" + std::to_string(set);
      auto j = prim.attributes.find(jname);
      auto w = prim.attributes.find(wname);
      if (j == prim.attributes.end() && w == prim.attributes.end()) break;
      if (j == prim.attributes.end() || w == prim.attributes.end())
        throw input_error(
            ctx.file, attributes,
            (j == prim.attributes.end() ? wname + " has no " + jname : jname + " has no " + wname) +
                " (skin attributes come in pairs)");
      const tinygltf::Accessor& ja = ctx.model.accessors[static_cast<size_t>(j->second)];
      const tinygltf::Accessor& wa = ctx.model.accessors[static_cast<size_t>(w->second)];
      const int jct = ja.componentType, wct = wa.componentType;
      check_vertex_accessor(ctx, j->second, TINYGLTF_TYPE_VEC4, n, pointer_join(attributes, jname),
                            "VEC4 UNSIGNED_BYTE or UNSIGNED_SHORT",
                            !ja.normalized && (jct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                               jct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
      check_vertex_accessor(ctx, w->second, TINYGLTF_TYPE_VEC4, n, pointer_join(attributes, wname),
                            "VEC4 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
                            wct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                                (wa.normalized && (wct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                   wct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
      joint_sets.push_back(read_accessor_floats(ctx.model, j->second, ctx.file));
      weight_sets.push_back(read_finite(ctx, w->second, pointer_join(attributes, wname), wname));
      weight_at.push_back(pointer_join(attributes, wname));
    }
    if (joint_sets.empty())
      throw input_error(ctx.file, attributes,
                        "the mesh is skinned by " + skin + " but has no JOINTS_0 and WEIGHTS_0");
    for (size_t v = 0; v < n; ++v) {
      dmat4 m(0.0);
      double sum = 0.0;
      for (size_t set = 0; set < joint_sets.size(); ++set)
        for (size_t c = 0; c < 4; ++c) {
          const double w = weight_sets[set][4 * v + c];
          if (w < 0.0)
            throw input_error(
                ctx.file, weight_at[set],
                "vertex " + std::to_string(v) + " has a negative weight (" + format_number(w) + ")");
          if (w == 0.0) continue;
          const size_t joint = static_cast<size_t>(joint_sets[set][4 * v + c]);
          if (joint >= joints.size())
            throw input_error(ctx.file, pointer_join(attributes, "JOINTS_" + std::to_string(set)),
                              "vertex " + std::to_string(v) + " names joint " + std::to_string(joint) +
                                  ", but " + skin + " has " + std::to_string(joints.size()) + " joints");
          m += w * joints[joint];
          sum += w;
        }
      if (!(sum > 0.0))
        throw input_error(ctx.file, weight_at[0],
                          "vertex " + std::to_string(v) + "'s joint weights are all zero");
      m /= sum;
      p[v] = dvec3(m * dvec4(p[v], 1.0));
      const dmat3 linear(m);
      if (!normals.empty()) normals[v] = glm::transpose(glm::inverse(linear)) * normals[v];
      if (!tangents.empty()) tangents[v] = linear * tangents[v];
    }
  }

  for (size_t i = 0; i < n; ++i) positions[i] = vec3(p[i]);
  for (size_t i = 0; i < normals.size(); ++i)
    for (int c = 0; c < 3; ++c) out.normals[3 * i + c] = static_cast<float>(normals[i][c]);
  for (size_t i = 0; i < tangents.size(); ++i)
    for (int c = 0; c < 3; ++c) out.tangents[4 * i + c] = static_cast<float>(tangents[i][c]);
  return out;
}

// Builds the kiln mesh of one glTF primitive, or -1 when it has nothing to render. With a
// deformation the mesh is the primitive posed by one node (see pose_primitive).
int32_t build_mesh(build_context& ctx, int mesh_index, int prim_index, const deformation* posed = nullptr) {
  const tinygltf::Mesh& src = ctx.model.meshes[static_cast<size_t>(mesh_index)];
  const tinygltf::Primitive& prim = src.primitives[static_cast<size_t>(prim_index)];
  const std::string where = primitive_pointer(mesh_index, prim_index);
  const std::string attributes = pointer_join(where, "attributes");

  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    ++ctx.out.stats.non_triangle_primitives_skipped;
    warn_once(ctx, "points and line primitives are not rendered; they are skipped");
    return -1;
  }

  // The mesh is charged for good; what reading the accessors needs on top of it is part of the
  // estimate too, since both are held at once.
  uint64_t bytes = primitive_bytes(ctx.model, prim);
  // Posing holds double copies of positions, normals and tangents, a delta and the skin sets.
  if (posed) bytes += ctx.model.accessors[static_cast<size_t>(prim.attributes.at("POSITION"))].count * 160;
  charge_memory(ctx.memory, bytes, ctx.file, "meshes");
  if (posed && ctx.memory) ctx.posed_bytes += bytes;

  mesh m;
  m.name = src.name.empty() ? "mesh " + std::to_string(mesh_index) : src.name;
  if (src.primitives.size() > 1) m.name += "/" + std::to_string(prim_index);

  const int position_accessor = prim.attributes.at("POSITION");
  const std::vector<float> pos =
      read_finite(ctx, position_accessor, pointer_join(attributes, "POSITION"), "POSITION");
  const size_t vertex_count = pos.size() / 3;
  m.positions.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) m.positions[i] = vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
  posed_attributes deformed;
  if (posed) {
    deformed = pose_primitive(ctx, prim, where, *posed, m.positions);
  }

  const std::vector<uint32_t> topology = primitive_indices(ctx, prim, vertex_count, where);
  const std::vector<uint32_t> tris = to_triangle_list(ctx, topology, prim.mode, where);

  // Drop degenerate triangles: a repeated vertex, or a zero (or non-finite) area. The cross
  // product is taken in double so that tiny but valid float triangles are kept.
  m.indices.reserve(tris.size());
  for (size_t t = 0; t + 2 < tris.size(); t += 3) {
    const uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
    const dvec3 pa(m.positions[a]), pb(m.positions[b]), pc(m.positions[c]);
    const double area2 = glm::length(glm::cross(pb - pa, pc - pa));
    if (a == b || b == c || a == c || !(area2 > 0.0) || !std::isfinite(area2)) {
      ++ctx.out.stats.degenerate_triangles_dropped;
      continue;
    }
    m.indices.insert(m.indices.end(), {a, b, c});
    m.bounds.extend(pa);
    m.bounds.extend(pb);
    m.bounds.extend(pc);
  }
  if (m.indices.empty()) return -1;
  // Object-space coordinates past the limit would put rays or boxes beyond Embree's range.
  if (!(max_abs_coordinate(m.bounds) <= max_coordinate))
    throw input_error(ctx.file, pointer_join(attributes, "POSITION"),
                      "a position reaches " + format_coordinate(max_abs_coordinate(m.bounds)) +
                          ", beyond kiln's coordinate limit of " + format_coordinate(max_coordinate));

  auto normal = prim.attributes.find("NORMAL");
  if (normal != prim.attributes.end()) {
    const std::vector<float> n =
        posed ? deformed.normals
              : read_finite(ctx, normal->second, pointer_join(attributes, "NORMAL"), "NORMAL");
    m.normals.resize(vertex_count);
    bool all_usable = true;
    for (size_t i = 0; i < vertex_count && all_usable; ++i) {
      const vec3 v(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
      const float len = glm::length(v);
      all_usable = len > 0.0f && std::isfinite(len);
      if (all_usable) m.normals[i] = v / len;
    }
    if (!all_usable) {
      m.normals.clear();
      warn_once(ctx,
                pointer_join(attributes, "NORMAL") + ": zero-length normals; the mesh uses flat normals");
    }
  }

  // UV sets are stored only when the material samples them.
  for (int set = 0; set < 2; ++set) {
    if (!material_samples_texcoord(ctx.model, prim.material, set)) continue;
    const std::string name = "TEXCOORD_" + std::to_string(set);
    auto uv = prim.attributes.find(name);
    if (uv == prim.attributes.end()) {
      warn_once(ctx, where + ": the material samples " + name + " but the primitive has none");
      continue;
    }
    const std::vector<float> t = read_finite(ctx, uv->second, pointer_join(attributes, name), name);
    std::vector<vec2>& out = set == 0 ? m.texcoords0 : m.texcoords1;
    out.resize(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) out[i] = vec2(t[2 * i], t[2 * i + 1]);
  }
  if (material_samples_other_texcoords(ctx.model, prim.material))
    warn_once(ctx,
              pointer("materials", prim.material) +
                  ": textures on TEXCOORD_2 or higher are not supported; they read TEXCOORD_0 positions");

  // Tangent frames only for materials that read one (normal maps, the clearcoat's normal map,
  // anisotropy): the file's TANGENT when it has one and smooth normals, generated from the UV set
  // of the first such texture otherwise. Without NORMAL the mesh is flat-shaded and glTF says to
  // ignore TANGENT; generated tangents then follow the faces.
  if (prim.material >= 0) {
    const int tangent_set = material_tangent_texcoord(ctx.model, prim.material);
    const std::vector<vec2>& uv = tangent_set == 1 ? m.texcoords1 : m.texcoords0;
    if (tangent_set >= 0 && uv.size() == vertex_count) {
      auto tangent = prim.attributes.find("TANGENT");
      if (tangent != prim.attributes.end() && !m.normals.empty()) {
        const std::vector<float> t =
            posed ? deformed.tangents
                  : read_finite(ctx, tangent->second, pointer_join(attributes, "TANGENT"), "TANGENT");
        m.tangents.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) {
          const vec3 v(t[4 * i], t[4 * i + 1], t[4 * i + 2]);
          const float len = glm::length(v);
          m.tangents[i] = len > 0.0f ? vec4(v / len, t[4 * i + 3] < 0.0f ? -1.0f : 1.0f) : vec4(0.0f);
        }
      } else {
        m.tangents = generate_tangents(m, uv);
      }
    }
  }

  // COLOR_0 always multiplies the base colour, so it is stored whenever present (already linear).
  auto color = prim.attributes.find("COLOR_0");
  if (color != prim.attributes.end()) {
    const std::vector<float> c =
        read_finite(ctx, color->second, pointer_join(attributes, "COLOR_0"), "COLOR_0");
    const size_t n =
        ctx.model.accessors[static_cast<size_t>(color->second)].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    m.colors0.resize(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i)
      m.colors0[i] = vec4(c[n * i], c[n * i + 1], c[n * i + 2], n == 4 ? c[n * i + 3] : 1.0f);
  }

  ctx.out.meshes.push_back(std::move(m));
  if (posed) ctx.posed_meshes.push_back(static_cast<uint32_t>(ctx.out.meshes.size() - 1));
  return static_cast<int32_t>(ctx.out.meshes.size() - 1);
}

// What a primitive's scene mesh is made of: its topology and every accessor build_mesh reads for
// it (UV sets only when its material samples them; tangents only for a normal-mapped material,
// generated from the normal texture's UV set when the file has none). Primitives with equal keys
// build equal meshes, so one is built and shared by their instances, which keep their own
// materials and transforms.
std::vector<int> geometry_key(const build_context& ctx, const tinygltf::Primitive& prim) {
  const auto attribute = [&](const char* name) {
    auto found = prim.attributes.find(name);
    return found == prim.attributes.end() ? -1 : found->second;
  };
  std::vector<int> key = {prim.mode, prim.indices, attribute("POSITION"), attribute("NORMAL"),
                          attribute("COLOR_0")};
  for (int set = 0; set < 2; ++set)
    key.push_back(material_samples_texcoord(ctx.model, prim.material, set)
                      ? attribute(set == 0 ? "TEXCOORD_0" : "TEXCOORD_1")
                      : -2);
  const int tangent_set = prim.material >= 0 ? material_tangent_texcoord(ctx.model, prim.material) : -1;
  key.push_back(tangent_set >= 0 ? tangent_set : -2);
  key.push_back(tangent_set >= 0 ? attribute("TANGENT") : -2);
  return key;
}

// A rigid mesh of a sequence's frame: the previous frame's, moved over (no animation changes it),
// or built when this is the first frame.
int32_t reused_or_built_mesh(build_context& ctx, int mesh_index, int prim_index,
                             const std::vector<int>& geometry) {
  if (ctx.reuse_geometry) {
    auto previous = ctx.reuse_geometry->find(geometry);
    if (previous != ctx.reuse_geometry->end()) {
      if (previous->second < 0) return -1;
      ctx.out.meshes.push_back(std::move(ctx.reuse->meshes[static_cast<size_t>(previous->second)]));
      return static_cast<int32_t>(ctx.out.meshes.size() - 1);
    }
  }
  return build_mesh(ctx, mesh_index, prim_index);
}

int32_t mesh_for(build_context& ctx, int mesh_index, int prim_index) {
  const auto key = std::make_pair(mesh_index, prim_index);
  auto cached = ctx.mesh_cache.find(key);
  if (cached != ctx.mesh_cache.end()) return cached->second;
  const tinygltf::Primitive& prim =
      ctx.model.meshes[static_cast<size_t>(mesh_index)].primitives[static_cast<size_t>(prim_index)];
  const std::vector<int> geometry = geometry_key(ctx, prim);
  auto shared = ctx.geometry_cache.find(geometry);
  const int32_t built = shared != ctx.geometry_cache.end()
                            ? shared->second
                            : reused_or_built_mesh(ctx, mesh_index, prim_index, geometry);
  ctx.geometry_cache.emplace(geometry, built);
  ctx.mesh_cache.emplace(key, built);
  return built;
}

// The morph weights a node's mesh is posed with: a weights channel's, else the node's `weights`,
// else the mesh's, else zeros (glTF 2.0 §3.7.2.2); empty when its mesh has no morph targets.
std::vector<double> morph_weights(build_context& ctx, int node_index) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const size_t targets = morph_target_count(ctx.model, node.mesh, ctx.file);
  if (targets == 0) return {};
  if (!ctx.pose.empty() && ctx.pose.nodes[static_cast<size_t>(node_index)].weights)
    return ctx.pose.nodes[static_cast<size_t>(node_index)].morph_weights;
  const tinygltf::Mesh& src = ctx.model.meshes[static_cast<size_t>(node.mesh)];
  const bool own = !node.weights.empty();
  const std::vector<double>& defaults = own ? node.weights : src.weights;
  if (defaults.empty()) return std::vector<double>(targets, 0.0);
  const std::string where = own ? pointer_join(pointer("nodes", node_index), "weights")
                                : pointer_join(pointer("meshes", node.mesh), "weights");
  if (defaults.size() != targets)
    throw input_error(ctx.file, where,
                      "has " + std::to_string(defaults.size()) + " weights but the mesh has " +
                          std::to_string(targets) + " morph targets");
  for (double w : defaults)
    if (!std::isfinite(w)) throw input_error(ctx.file, where, "a weight is NaN or infinite");
  return defaults;
}

// Every node's world transform in the pose, from the roots of the whole node forest (a skin's
// joints need not lie in the rendered scene).
void compute_node_worlds(build_context& ctx) {
  const size_t count = ctx.model.nodes.size();
  std::vector<char> is_child(count, 0);
  for (const tinygltf::Node& node : ctx.model.nodes)
    for (int child : node.children) is_child[static_cast<size_t>(child)] = 1;
  ctx.node_world.assign(count, dmat4(1.0));
  std::vector<std::pair<int, dmat4>> stack;
  for (size_t n = count; n-- > 0;)
    if (!is_child[n]) stack.emplace_back(static_cast<int>(n), dmat4(1.0));
  while (!stack.empty()) {
    const auto [node_index, parent_world] = stack.back();
    stack.pop_back();
    const dmat4 world = parent_world * posed_local(ctx, node_index);
    ctx.node_world[static_cast<size_t>(node_index)] = world;
    for (int child : ctx.model.nodes[static_cast<size_t>(node_index)].children)
      stack.emplace_back(child, world);
  }
}

// The joint matrices of a skin: world(joint) * inverseBindMatrix (identity when absent).
const std::vector<dmat4>& skin_joint_matrices(build_context& ctx, int skin_index) {
  auto cached = ctx.skin_joints.find(skin_index);
  if (cached != ctx.skin_joints.end()) return cached->second;
  if (ctx.node_world.empty()) compute_node_worlds(ctx);
  const tinygltf::Skin& skin = ctx.model.skins[static_cast<size_t>(skin_index)];
  const std::string where = pointer("skins", skin_index);
  if (skin.joints.empty())
    throw input_error(ctx.file, pointer_join(where, "joints"), "a skin needs at least one joint");
  std::vector<float> inverse_bind;
  if (skin.inverseBindMatrices >= 0) {
    const std::string at = pointer_join(where, "inverseBindMatrices");
    const tinygltf::Accessor& acc = ctx.model.accessors[static_cast<size_t>(skin.inverseBindMatrices)];
    if (acc.type != TINYGLTF_TYPE_MAT4 || acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      throw input_error(ctx.file, at,
                        "must be MAT4 FLOAT (got " + type_name(acc.type) + " " +
                            component_type_name(acc.componentType) + ")");
    if (acc.count < skin.joints.size())
      throw input_error(ctx.file, at,
                        "has " + std::to_string(acc.count) + " matrices for " +
                            std::to_string(skin.joints.size()) + " joints");
    inverse_bind = read_finite(ctx, skin.inverseBindMatrices, at, "inverseBindMatrices");
  }
  std::vector<dmat4> joints(skin.joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    dmat4 ibm(1.0);
    if (!inverse_bind.empty())
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ibm[c][r] = inverse_bind[16 * j + static_cast<size_t>(4 * c + r)];
    joints[j] = ctx.node_world[static_cast<size_t>(skin.joints[j])] * ibm;
  }
  return ctx.skin_joints.emplace(skin_index, std::move(joints)).first->second;
}

// How the node deforms its mesh, or nothing when it is placed rigidly (no skin, no weights
// channel, all morph weights zero): then its primitives are the shared meshes every other node
// uses.
std::optional<deformation> node_deformation(build_context& ctx, int node_index) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  deformation d;
  d.weights = morph_weights(ctx, node_index);
  // Weights a channel drives keep their posed mesh even when all are zero at this time, so which
  // meshes a scene has does not depend on the time (frames of one shot share the structure).
  const bool animated = !ctx.pose.empty() && ctx.pose.nodes[static_cast<size_t>(node_index)].weights;
  if (!animated && std::all_of(d.weights.begin(), d.weights.end(), [](double w) { return w == 0.0; }))
    d.weights.clear();
  if (node.skin >= 0) {
    d.skin = node.skin;
    d.joints = &skin_joint_matrices(ctx, node.skin);
  }
  if (d.weights.empty() && d.joints == nullptr) return std::nullopt;
  return d;
}

// The scene mesh of a node's primitive: its own posed mesh when the node deforms it, else the
// shared one.
int32_t mesh_for_node(build_context& ctx, int node_index, int prim_index, const deformation* posed) {
  const int mesh_index = ctx.model.nodes[static_cast<size_t>(node_index)].mesh;
  if (posed == nullptr) return mesh_for(ctx, mesh_index, prim_index);
  const auto key = std::make_pair(node_index, prim_index);
  auto cached = ctx.posed_cache.find(key);
  if (cached != ctx.posed_cache.end()) return cached->second;
  const int32_t built = build_mesh(ctx, mesh_index, prim_index, posed);
  ctx.posed_cache.emplace(key, built);
  ctx.posed_primitives.emplace(mesh_index, prim_index);
  return built;
}

// Places every primitive of the node's mesh at `world`; false (nothing placed) when `world` is
// singular. Primitives are built first, so their data is checked even when nothing is placed.
bool place_primitives(build_context& ctx, int node_index, const dmat4& world, const std::string& where,
                      const deformation* posed) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const tinygltf::Mesh& src = ctx.model.meshes[static_cast<size_t>(node.mesh)];
  instance inst;
  inst.kind = shape_kind::mesh;
  inst.node = static_cast<uint32_t>(node_index);
  inst.world_from_object = world;
  finish_instance_transform(inst);
  const bool singular = !is_finite(inst.object_from_world) || glm::determinant(dmat3(world)) == 0.0;
  if (!singular)
    if (auto problem = transform_range_problem(world))
      throw input_error(ctx.file, where, "its world transform is out of range: " + *problem);
  for (size_t p = 0; p < src.primitives.size(); ++p) {
    const int32_t shape = mesh_for_node(ctx, node_index, static_cast<int>(p), posed);
    if (shape < 0 || singular) continue;
    inst.shape = static_cast<uint32_t>(shape);
    ctx.out.instances.push_back(inst);
    ctx.instance_gltf_material.push_back(src.primitives[p].material);
  }
  return !singular;
}

// A node's mesh: placed once, or once per EXT_mesh_gpu_instancing instance at
// world * node_from_instance (the node's transform is the instances' parent). A skinned mesh is
// posed in world space by its joints, so the node's own transform is ignored (glTF 2.0 §3.7.3).
void place_mesh(build_context& ctx, int node_index, const dmat4& node_world) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const std::optional<deformation> posed = node_deformation(ctx, node_index);
  const deformation* deform = posed ? &*posed : nullptr;
  const dmat4 world = node.skin >= 0 ? dmat4(1.0) : node_world;
  const instance_budget budget{ctx.out.instances.size(),
                               ctx.model.meshes[static_cast<size_t>(node.mesh)].primitives.size(),
                               ctx.max_instances};
  const auto instances = read_gpu_instances(ctx.model, node_index, ctx.quantized, budget, ctx.file);
  if (!instances) {
    if (!place_primitives(ctx, node_index, world, range_pointer(node, node_index), deform))
      warn_once(ctx,
                pointer("nodes", node_index) + ": singular transform (zero scale); its mesh is not placed");
    return;
  }
  size_t singular = 0;
  const std::string where =
      pointer_join(pointer_join(pointer("nodes", node_index), "extensions"), gpu_instancing_extension);
  for (const dmat4& node_from_instance : *instances)
    singular += !place_primitives(ctx, node_index, world * node_from_instance, where, deform);
  if (singular != 0)
    warn_once(ctx, pointer_join(pointer_join(pointer("nodes", node_index), "extensions"),
                                gpu_instancing_extension) +
                       ": " + std::to_string(singular) +
                       " instances have a singular transform (zero scale); they are not placed");
}

// A KILN_quadric placement: one instance of a shared definition. Unlike a mesh, a quadric
// with a singular transform is an error: its object-space ray would be undefined.
void place_quadric(build_context& ctx, int node_index, const quadric_placement& placement,
                   const dmat4& world) {
  instance inst;
  inst.kind = shape_kind::quadric;
  inst.shape = placement.primitive;
  inst.node = static_cast<uint32_t>(node_index);
  inst.world_from_object = world;
  finish_instance_transform(inst);
  if (!is_finite(inst.object_from_world) || glm::determinant(dmat3(world)) == 0.0)
    throw input_error(
        ctx.file, pointer_join(pointer_join(pointer("nodes", node_index), "extensions"), quadric_extension),
        "the node's transform is not invertible (zero scale); a quadric cannot be placed by it");
  if (auto problem = transform_range_problem(world))
    throw input_error(ctx.file, range_pointer(ctx.model.nodes[static_cast<size_t>(node_index)], node_index),
                      "its world transform is out of range: " + *problem);
  ctx.out.instances.push_back(inst);
  ctx.instance_gltf_material.push_back(placement.material);
}

// A camera frame without scale: keep the view direction (-Z) and the up vector (+Y) of the node.
void place_camera(build_context& ctx, int node_index, const dmat4& world) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const tinygltf::Camera& src = ctx.model.cameras[static_cast<size_t>(node.camera)];
  const dvec3 z = glm::normalize(dvec3(world[2]));
  const dvec3 y_raw = dvec3(world[1]) - glm::dot(dvec3(world[1]), z) * z;
  const dvec3 y = glm::normalize(y_raw);
  const dvec3 x = glm::cross(y, z);
  if (!is_finite(z) || !is_finite(y) || !is_finite(x) || glm::length(y_raw) == 0.0) {
    warn_once(ctx,
              pointer("nodes", node_index) + ": camera node transform is singular; the camera is skipped");
    return;
  }
  check_node_position(ctx, node_index, world, "camera");
  camera cam;
  cam.name = !src.name.empty() ? src.name : node.name;
  cam.world_from_camera = dmat4(dvec4(x, 0.0), dvec4(y, 0.0), dvec4(z, 0.0), dvec4(dvec3(world[3]), 1.0));
  if (src.type == "perspective") {
    cam.kind = projection::perspective;
    cam.yfov = static_cast<float>(src.perspective.yfov);
    cam.aspect_ratio = static_cast<float>(src.perspective.aspectRatio);
    cam.znear = static_cast<float>(src.perspective.znear);
  } else {
    cam.kind = projection::orthographic;
    // The view's half-extents become ray origins: they obey the coordinate limit too.
    for (const auto& [key, value] :
         {std::pair{"xmag", src.orthographic.xmag}, std::pair{"ymag", src.orthographic.ymag}})
      if (!(std::abs(value) <= max_coordinate))
        throw input_error(ctx.file,
                          pointer_join(pointer_join(pointer("cameras", node.camera), "orthographic"), key),
                          format_coordinate(value) + " is beyond kiln's coordinate limit of " +
                              format_coordinate(max_coordinate));
    cam.xmag = static_cast<float>(src.orthographic.xmag);
    cam.ymag = static_cast<float>(src.orthographic.ymag);
    cam.znear = static_cast<float>(src.orthographic.znear);
  }
  ctx.out.cameras.push_back(cam);
}

void place_light(build_context& ctx, int node_index, int light_index, const dmat4& world) {
  const tinygltf::Light& src = ctx.model.lights[static_cast<size_t>(light_index)];
  light l;
  l.name = src.name;
  l.kind = src.type == "spot"          ? light_kind::spot
           : src.type == "directional" ? light_kind::directional
                                       : light_kind::point;
  if (src.color.size() == 3)
    l.color = vec3(static_cast<float>(src.color[0]), static_cast<float>(src.color[1]),
                   static_cast<float>(src.color[2]));
  l.intensity = static_cast<float>(src.intensity);
  l.range = static_cast<float>(src.range);
  l.inner_cone_angle = static_cast<float>(src.spot.innerConeAngle);
  l.outer_cone_angle = static_cast<float>(src.spot.outerConeAngle);
  if (l.kind != light_kind::directional) check_node_position(ctx, node_index, world, "light");
  l.position = transform_point(world, dvec3(0.0));
  const dvec3 dir = transform_vector(world, dvec3(0.0, 0.0, -1.0));
  const double len = glm::length(dir);
  if (l.kind != light_kind::point) {
    if (!(len > 0.0) || !std::isfinite(len)) {
      warn_once(ctx,
                pointer("nodes", node_index) + ": light node transform is singular; the light is skipped");
      return;
    }
    l.direction = vec3(dir / len);
  }
  ctx.out.lights.push_back(l);
}

// Walks the scene's node forest iteratively (validation proved it acyclic) in document order.
void place_nodes(build_context& ctx, const std::vector<int>& roots) {
  std::vector<std::pair<int, dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, dmat4(1.0));
  while (!stack.empty()) {
    const auto [node_index, parent_world] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
    const dmat4 world = parent_world * posed_local(ctx, node_index);
    if (!is_finite(world))
      throw input_error(ctx.file, pointer("nodes", node_index), "world transform overflows to infinity");
    if (node.mesh >= 0) place_mesh(ctx, node_index, world);
    if (auto placement = read_quadric_placement(ctx.model, node_index, ctx.out.quadrics.size(), ctx.file))
      place_quadric(ctx, node_index, *placement, world);
    if (node.camera >= 0) place_camera(ctx, node_index, world);
    const int light_index = node_light_index(node);
    if (light_index >= 0) place_light(ctx, node_index, light_index, world);
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, world);
  }
}

// The scene material of each glTF material the instances use (-1: the default material).
using material_map = std::map<int, uint32_t>;

std::set<int> used_materials(const build_context& ctx) {
  return std::set<int>(ctx.instance_gltf_material.begin(), ctx.instance_gltf_material.end());
}

// Converts the materials instances use, in glTF order, then the default material last if needed.
material_map convert_used_materials(build_context& ctx) {
  const std::set<int> used = used_materials(ctx);
  texture_remap remap = make_texture_remap(ctx.model);
  remap.max_texels = ctx.max_texels;
  remap.memory = ctx.memory;
  material_map scene_index;
  try {
    for (int gltf_material : used) {
      if (gltf_material < 0) continue;
      ctx.out.materials.push_back(convert_material(ctx.model, gltf_material, remap, ctx.out, ctx.file));
      ctx.out.materials.back().source_index = gltf_material;
      scene_index[gltf_material] = static_cast<uint32_t>(ctx.out.materials.size() - 1);
    }
  } catch (...) {
    // Images used to decode as materials converted: one queued before this error that does not
    // decode is still the error reported, whatever the thread count.
    decode_used_images(remap, ctx.out, ctx.file, ctx.threads);
    throw;
  }
  decode_used_images(remap, ctx.out, ctx.file, ctx.threads);
  if (used.count(-1) != 0 || ctx.out.materials.empty()) {
    ctx.out.materials.push_back(default_material());
    ctx.out.materials.back().source_index = static_cast<int32_t>(ctx.model.materials.size());
    scene_index[-1] = static_cast<uint32_t>(ctx.out.materials.size() - 1);
  }
  return scene_index;
}

void assign_materials(build_context& ctx, const material_map& scene_index) {
  for (size_t i = 0; i < ctx.out.instances.size(); ++i)
    ctx.out.instances[i].material = scene_index.at(ctx.instance_gltf_material[i]);
}

// Index values are checked while a primitive is built; primitives the chosen scene does not
// place are never built, yet an out-of-range index there still marks a broken file.
void check_unplaced_indices(build_context& ctx) {
  for (size_t m = 0; m < ctx.model.meshes.size(); ++m) {
    const auto& primitives = ctx.model.meshes[m].primitives;
    for (size_t p = 0; p < primitives.size(); ++p) {
      const auto key = std::make_pair(static_cast<int>(m), static_cast<int>(p));
      if (ctx.mesh_cache.count(key) != 0 || ctx.posed_primitives.count(key) != 0 || primitives[p].indices < 0)
        continue;
      const size_t vertex_count =
          ctx.model.accessors[static_cast<size_t>(primitives[p].attributes.at("POSITION"))].count;
      primitive_indices(ctx, primitives[p], vertex_count, primitive_pointer(key.first, key.second));
    }
  }
}

int chosen_scene(const tinygltf::Model& model, const gltf_load_options& options, const std::string& file) {
  const int count = static_cast<int>(model.scenes.size());
  const auto missing = [&](int index, const std::string& where) {
    return input_error(file, where,
                       "/scenes/" + std::to_string(index) + " does not exist (file has " +
                           std::to_string(count) + " scenes)");
  };
  if (options.scene_index >= 0) {
    if (options.scene_index >= count) throw missing(options.scene_index, "");
    return options.scene_index;
  }
  if (model.defaultScene >= 0) return model.defaultScene;  // validated to be in range
  return count > 0 ? 0 : -1;
}

}  // namespace

// What a sequence keeps between frames: the parsed file, and what its last frame was built from.
struct gltf_sequence::state {
  std::string path;
  gltf_load_options options;
  memory_charge model_memory;  // released once the model is gone
  tinygltf::Model model;
  bool quantized = false;
  std::vector<int> animations;  // the chosen ones; empty: the file is posed without animations
  bool animated = false;
  std::set<std::string> warned;  // across frames: each distinct warning once per sequence
  // The last frame's:
  bool posed_once = false;
  std::map<std::vector<int>, int32_t> geometry_cache;
  std::set<int> used;
  material_map materials;
  size_t image_count = 0;  // images the loader made (a client may append its own)
  uint64_t posed_bytes = 0;

  state(const std::string& p, const gltf_load_options& o) : path(p), options(o), model_memory(o.memory) {}
};

gltf_sequence::gltf_sequence(const std::string& path, const gltf_load_options& options)
    : state_(std::make_unique<state>(path, options)) {
  state& st = *state_;
  st.model = parse_gltf_file(path, options, &st.model_memory);
  // Compressed data is decoded into buffers of its own first, so that validation checks it like
  // any stored data: meshopt bufferViews (which a Draco stream could sit in), then Draco.
  decode_meshopt_views(st.model, path, &st.model_memory);
  decode_draco_primitives(st.model, path, &st.model_memory);
  validate_model(st.model, path);
  apply_material_variant(st.model, options.variant, path);
  st.quantized = uses_extension(st.model, quantization_extension);
  // A still asset (no animation) skips this: its scene is what it always was.
  st.animated = !st.model.animations.empty() ||
                !(options.animation.empty() || options.animation == "all" || options.animation == "none");
  if (st.animated) st.animations = chosen_animations(st.model, options.animation, path);
}

gltf_sequence::~gltf_sequence() = default;

bool gltf_sequence::animated() const { return state_->animated && !state_->animations.empty(); }

std::pair<double, double> gltf_sequence::time_range() const {
  if (!animated()) return {0.0, 0.0};
  return animation_time_range(state_->model, state_->animations, state_->path);
}

scene gltf_sequence::pose(double time, scene* previous, std::vector<uint32_t>* posed_meshes) {
  state& st = *state_;
  const tinygltf::Model& model = st.model;
  const std::string& path = st.path;
  const bool reuse = previous != nullptr && st.posed_once;
  scene out;
  out.source = path;
  build_context ctx{model,
                    path,
                    st.options.limits.max_instances,
                    st.options.limits.max_texels,
                    st.options.threads,
                    st.quantized,
                    out,
                    {},
                    {},
                    st.warned};
  ctx.memory = st.options.memory;
  if (reuse) {
    ctx.reuse = previous;
    ctx.reuse_geometry = &st.geometry_cache;
  }

  // Optional extensions kiln does not know are ignored, all named on one line (required ones
  // were refused while parsing).
  const auto& supported = supported_extensions();
  std::vector<std::string> unsupported;
  for (const std::string& name : model.extensionsUsed)
    if (std::find(supported.begin(), supported.end(), name) == supported.end())
      unsupported.push_back(shown(name));
  if (unsupported.size() == 1)
    warn_once(ctx, "extension " + unsupported[0] + " is not supported; it is ignored");
  if (unsupported.size() > 1) {
    std::string names = unsupported[0];
    for (size_t i = 1; i < unsupported.size(); ++i) names += ", " + unsupported[i];
    warn_once(ctx, "extensions " + names + " are not supported; they are ignored");
  }
  if (!std::isfinite(time)) throw input_error(path, "--time", "the time must be a finite number of seconds");
  if (st.animated) {
    ctx.pose = evaluate_animations(model, st.animations, time, path);
    for (const std::string& warning : ctx.pose.warnings) warn_once(ctx, warning);
  }

  out.quadrics = read_quadric_definitions(model, path);
  out.node_names.reserve(model.nodes.size());
  for (const tinygltf::Node& node : model.nodes) out.node_names.push_back(node.name);
  const int scene_index = chosen_scene(model, st.options, path);
  if (scene_index < 0)
    warn_once(ctx, "the file has no scenes; nothing is placed");
  else
    place_nodes(ctx, model.scenes[static_cast<size_t>(scene_index)].nodes);
  if (!reuse) check_unplaced_indices(ctx);  // the file does not change between frames

  // Materials do not animate: a frame that uses the same ones as the last takes them over, with
  // their textures and decoded images.
  const std::set<int> used = used_materials(ctx);
  if (reuse && used == st.used) {
    out.materials = std::move(previous->materials);
    out.textures = std::move(previous->textures);
    const size_t images = std::min(st.image_count, previous->images.size());
    out.images.assign(
        std::make_move_iterator(previous->images.begin()),
        std::make_move_iterator(previous->images.begin() + static_cast<std::ptrdiff_t>(images)));
  } else {
    st.materials = convert_used_materials(ctx);
    st.used = used;
  }
  assign_materials(ctx, st.materials);
  st.image_count = out.images.size();

  // The last frame's posed meshes are the caller's to drop now; this frame's are charged instead.
  if (ctx.memory) ctx.memory->release(st.posed_bytes);
  st.posed_bytes = ctx.posed_bytes;
  st.geometry_cache = std::move(ctx.geometry_cache);
  st.posed_once = true;
  if (posed_meshes) *posed_meshes = std::move(ctx.posed_meshes);
  return out;
}

std::vector<std::string> gltf_material_variants(const std::string& path, const gltf_load_options& options) {
  memory_charge held(options.memory);
  const tinygltf::Model model = parse_gltf_file(path, options, &held);
  return material_variant_names(model, path);
}

scene load_gltf(const std::string& path, const gltf_load_options& options) {
  gltf_sequence sequence(path, options);
  return sequence.pose(options.time);
}

}  // namespace kiln
