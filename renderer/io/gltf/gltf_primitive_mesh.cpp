// Builds the scene mesh of one glTF primitive: reads and checks its indices and attributes,
// turns strips and fans into triangle lists, poses it by a node's morph weights and skin when it
// deforms, generates tangents a normal map needs, and shares one mesh among primitives built from
// the same accessors (see gltf_build_context.h for what the loader hands it).
#include "io/gltf/gltf_primitive_mesh.h"

#include <cmath>
#include <utility>

#include "core/error.h"
#include "core/format_number.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_materials.h"
#include "io/gltf/gltf_memory.h"
#include "io/gltf/mesh_tangents.h"
#include "scene/coordinate_range.h"

namespace kiln::gltf_internal {
namespace {

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
  // NORMAL and TANGENT as read (kept for the caller) and as directions to deform (xyz of a stride).
  const auto read_directions = [&](const char* name, size_t stride, std::vector<float>& read,
                                   std::vector<dvec3>& directions) {
    auto found = prim.attributes.find(name);
    if (found == prim.attributes.end()) return;
    read = read_finite(ctx, found->second, pointer_join(attributes, name), name);
    directions.resize(n);
    for (size_t i = 0; i < n; ++i)
      directions[i] = dvec3(read[stride * i], read[stride * i + 1], read[stride * i + 2]);
  };
  read_directions("NORMAL", 3, out.normals, normals);
  read_directions("TANGENT", 4, out.tangents, tangents);

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
    if (previous != ctx.reuse_geometry->end()) return take_over_mesh(ctx, previous->second);
  }
  return build_mesh(ctx, mesh_index, prim_index);
}

}  // namespace

int32_t take_over_mesh(build_context& ctx, int32_t previous) {
  if (previous < 0) return -1;
  ctx.out.meshes.push_back(std::move(ctx.reuse->meshes[static_cast<size_t>(previous)]));
  return static_cast<int32_t>(ctx.out.meshes.size() - 1);
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

// Builds the kiln mesh of one glTF primitive, or -1 when it has nothing to render. With a
// deformation the mesh is the primitive in that pose (see pose_primitive).
int32_t build_mesh(build_context& ctx, int mesh_index, int prim_index, const deformation* posed) {
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
  charge_memory(ctx.memory, bytes, ctx.file,
                posed ? "posed meshes (one per distinct skin and morph pose)" : "meshes");
  // A pose that moves is built again for every time: the last time's is released as this one is charged.
  if (posed && posed->moves && ctx.memory) ctx.posed_bytes += bytes;

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
  if (posed && posed->moves) ctx.posed_meshes.push_back(static_cast<uint32_t>(ctx.out.meshes.size() - 1));
  return static_cast<int32_t>(ctx.out.meshes.size() - 1);
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

}  // namespace kiln::gltf_internal
